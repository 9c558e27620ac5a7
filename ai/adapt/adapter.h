#pragma once
// One adaptive NPC: after each round it measures the player, asks its proposer (the model,
// the rubber band, or nobody) for the next NPC, and lets the guards decide what it becomes.
// The zone's duels, the evaluation and the benchmark all adapt through this one class.

#include <cstdint>
#include <optional>

#include "ai/adapt/duel.h"
#include "ai/adapt/duel_model.h"
#include "ai/adapt/features.h"
#include "ai/adapt/guards.h"
#include "ai/adapt/rubber_band.h"

namespace zonesim::ai::adapt {

/// Who proposes the next NPC.
enum class AdaptMode { Off, RubberBand, Model };

/// How an adapter adapts.
struct AdaptSettings {
  AdaptMode mode = AdaptMode::Off;
  double target_win_rate = 0.5;  ///< the share of rounds the player should win
  GuardLimits guard;
  int band_window = 10;    ///< rounds the rubber band looks back over
  double band_gain = 0.5;  ///< difficulty per unit of the player's lead
};

/// Adapts one NPC to one player.
class DuelAdapter {
 public:
  /// `model` must outlive the adapter; it is required in Model mode (checked).
  DuelAdapter(const AdaptSettings& settings, const DuelModel* model);

  /// The NPC for the next round.
  const NpcParams& params() const { return params_; }
  /// One adaptation step after a round.
  void onRound(const RoundResult& r);
  /// Steps with a proposal from outside (a test's adversarial model output).
  void propose(const NpcParams& proposed) { params_ = guard_.step(params_, proposed); }
  /// The player's measure so far.
  const PlayerFeatures& features() const { return features_; }
  /// What the guards did.
  const GuardStats& guardStats() const { return guard_.stats(); }

 private:
  AdaptSettings settings_;
  const DuelModel* model_;
  PlayerFeatures features_;
  RubberBand band_;
  AdaptGuard guard_;
  NpcParams params_;
};

}  // namespace zonesim::ai::adapt
