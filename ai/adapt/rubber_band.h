#pragma once
// The baseline: rubber banding. Over the last `window` rounds, the side that trails gets help
// in proportion to how far behind it is: the NPC eases off by `gain` times the player's
// deficit (losses minus wins, as a fraction of the window), and presses by as much when it
// trails. No learning and no memory beyond the window.

#include <cstddef>
#include <vector>

namespace zonesim::ai::adapt {

/// Rubber banding over a window of recent rounds.
class RubberBand {
 public:
  /// `window` >= 1 rounds; `gain`: difficulty per unit of deficit.
  RubberBand(int window, double gain);

  /// Records a round's outcome.
  void record(bool player_won);
  /// The difficulty it asks for now (not clamped: the guards do that).
  double difficulty() const;

 private:
  std::vector<signed char> outcomes_;  // ring: +1 player won, -1 NPC won
  std::size_t next_ = 0;
  int balance_ = 0;  // sum of the ring: player wins minus NPC wins
  double gain_;
};

}  // namespace zonesim::ai::adapt
