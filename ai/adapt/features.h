#pragma once
// The player's measured performance: its hit rate over recent rounds, older ones fading. It is
// what the model reads instead of the hidden skill, and it does not depend on the NPC met, so
// the model can ask "how would this player fare against that NPC" for any NPC.

#include <cstdint>

#include "ai/adapt/duel.h"

namespace zonesim::ai::adapt {

/// More attacks than a round can hold: not a real round.
constexpr double kMaxAttacks = kMaxExchanges;

/// A running measure of one player's performance.
class PlayerFeatures {
 public:
  /// `smoothing`: how much of the past fades per round, in (0, 1].
  explicit PlayerFeatures(double smoothing = 0.05);

  /// Adds one round; a result that cannot be real (negative counts, more hits than attacks,
  /// no attacks) is refused and counted, and the measure stays as it was.
  bool observe(const RoundResult& r);
  /// Adds one round's counts; non-finite, negative, more hits than attacks, or more attacks
  /// than a round can hold is refused and counted.
  bool observeCounts(double hits, double attacks);
  /// The measured hit rate; meaningless before the first round (see rounds()).
  double hitRate() const { return attacks_ > 0 ? hits_ / attacks_ : 0; }
  /// Rounds accepted.
  std::uint64_t rounds() const { return rounds_; }
  /// Rounds refused as impossible.
  std::uint64_t refused() const { return refused_; }

 private:
  double smoothing_;
  double hits_ = 0;  // faded sums over the rounds seen
  double attacks_ = 0;
  std::uint64_t rounds_ = 0;
  std::uint64_t refused_ = 0;
};

}  // namespace zonesim::ai::adapt
