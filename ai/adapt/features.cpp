#include "ai/adapt/features.h"

#include <cmath>

namespace zonesim::ai::adapt {

PlayerFeatures::PlayerFeatures(double smoothing) : smoothing_(smoothing) {}

bool PlayerFeatures::observe(const RoundResult& r) {
  if (r.player_attacks <= 0 || r.player_hits < 0 || r.player_hits > r.player_attacks) {
    ++refused_;
    return false;
  }
  return observeCounts(double(r.player_hits), double(r.player_attacks));
}

bool PlayerFeatures::observeCounts(double hits, double attacks) {
  if (!std::isfinite(hits) || !std::isfinite(attacks) || attacks <= 0 || attacks > kMaxAttacks ||
      hits < 0 || hits > attacks) {
    ++refused_;
    return false;
  }
  // Hits over attacks, both summed with fading weights: a ratio per round would be biased by
  // when rounds stop (a round ends on a hit), and by how hard the NPC made them end early.
  hits_ = (1 - smoothing_) * hits_ + hits;
  attacks_ = (1 - smoothing_) * attacks_ + attacks;
  ++rounds_;
  return true;
}

}  // namespace zonesim::ai::adapt
