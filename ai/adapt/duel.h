#pragma once
// A duel between a simulated player and an NPC, as exchanges: in each, the player attacks
// (hitting with its accuracy), then the NPC attacks with its aggression (ramping up from 0
// over its reaction time) and hits with its accuracy. The first to land kHitsToWin hits wins the
// round. One exchange is one zone tick; training and evaluation play whole rounds at once.

#include <cstdint>

#include "ai/adapt/npc_params.h"
#include "common/rng.h"

namespace zonesim::ai::adapt {

/// Hits that end a round.
constexpr int kHitsToWin = 5;
/// A round still open after this many exchanges goes to the NPC (a player who cannot finish
/// it has not won), so a round always ends.
constexpr int kMaxExchanges = 400;

/// A simulated player's accuracy for skill in [0, 1] (weak to strong).
double playerAccuracy(double skill);

/// How a round went, as the game measures it.
struct RoundResult {
  bool player_won = false;
  int player_attacks = 0;
  int player_hits = 0;
  int npc_hits = 0;
};

/// One round in progress.
class DuelRound {
 public:
  /// Plays one exchange; true when the round is over (then result() is final).
  bool exchange(Pcg32& rng, double player_accuracy, const NpcParams& npc);
  /// The round so far.
  const RoundResult& result() const { return result_; }
  /// Exchanges played.
  int exchanges() const { return exchanges_; }

 private:
  RoundResult result_;
  int exchanges_ = 0;
};

/// Plays a whole round.
RoundResult playRound(Pcg32& rng, double player_accuracy, const NpcParams& npc);

}  // namespace zonesim::ai::adapt
