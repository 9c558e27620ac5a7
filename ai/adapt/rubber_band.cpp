#include "ai/adapt/rubber_band.h"

#include <stdexcept>

#include "ai/adapt/npc_params.h"

namespace zonesim::ai::adapt {

RubberBand::RubberBand(int window, double gain) : gain_(gain) {
  if (window < 1) throw std::invalid_argument("rubber band window must be at least 1 round");
  outcomes_.assign(std::size_t(window), 0);
}

void RubberBand::record(bool player_won) {
  balance_ -= outcomes_[next_];
  outcomes_[next_] = player_won ? 1 : -1;
  balance_ += outcomes_[next_];
  next_ = (next_ + 1) % outcomes_.size();
}

double RubberBand::difficulty() const {
  // The player's lead as a fraction of the window: negative when the player trails.
  const double lead = double(balance_) / double(outcomes_.size());
  return kDefaultDifficulty + gain_ * lead;
}

}  // namespace zonesim::ai::adapt
