#include "ai/adapt/duel.h"

#include <algorithm>

namespace zonesim::ai::adapt {

double playerAccuracy(double skill) {
  return 0.2 + 0.6 * skill;
}

bool DuelRound::exchange(Pcg32& rng, double player_accuracy, const NpcParams& npc) {
  ++exchanges_;
  ++result_.player_attacks;
  // The player strikes first in an exchange: two killing blows in one exchange go to it.
  if (rng.uniform() < player_accuracy && ++result_.player_hits >= kHitsToWin) {
    result_.player_won = true;
    return true;
  }
  // The NPC warms up over its reaction time: a ramp, not a step, so that win chances change
  // smoothly with the reaction time (a model fits them, and no tiny change flips a round).
  const double ready = std::min(1.0, exchanges_ / (npc.reaction_steps + 1));
  // Both draws are made every exchange, so one player's stream does not depend on the NPC.
  const double attack = rng.uniform(), hit = rng.uniform();
  if (attack < npc.aggression * ready && hit < npc.accuracy && ++result_.npc_hits >= kHitsToWin)
    return true;
  return exchanges_ >= kMaxExchanges;
}

RoundResult playRound(Pcg32& rng, double player_accuracy, const NpcParams& npc) {
  DuelRound round;
  while (!round.exchange(rng, player_accuracy, npc)) {
  }
  return round.result();
}

}  // namespace zonesim::ai::adapt
