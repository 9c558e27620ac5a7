#pragma once
// Measures what adaptation achieves: players of given skills play rounds against adaptive NPCs
// and their win rates are counted, per skill. Seeded, so a figure is the same on every run.

#include <cstdint>
#include <vector>

#include "ai/adapt/adapter.h"

namespace zonesim::ai::adapt {

/// One skill's outcome.
struct SkillOutcome {
  double skill = 0;
  std::uint64_t rounds = 0;
  std::uint64_t player_wins = 0;
  std::uint64_t fallbacks = 0;  ///< guard fallbacks to the defaults
  /// Wins per round.
  double winRate() const { return rounds ? double(player_wins) / double(rounds) : 0; }
};

/// An evaluation run.
struct EvalOptions {
  std::uint64_t seed = 11;  ///< another seed than training's: fresh play
  int players_per_skill = 20;
  int rounds_per_player = 100;
};

/// Plays every skill under `settings` (and `model` in Model mode).
std::vector<SkillOutcome> evaluate(const std::vector<double>& skills, const AdaptSettings& settings,
                                   const DuelModel* model, const EvalOptions& options);

}  // namespace zonesim::ai::adapt
