#include "physics/constraint_colouring.h"

#include <algorithm>
#include <bit>

namespace zonesim::physics {

void ConstraintColouring::build(std::span<const ConstraintBodies> constraints,
                                std::size_t body_count) {
  body_colours_.assign(body_count, 0);
  colour_of_.resize(constraints.size());
  std::vector<std::uint32_t>& count = next_lane_;
  count.assign(kMaxColours, 0);
  overflow_ = 0;
  for (std::size_t c = 0; c < constraints.size(); ++c) {
    const ConstraintBodies& k = constraints[c];
    std::uint64_t used = 0;
    if (k.a_moves) used |= body_colours_[k.a];
    if (k.b_moves) used |= body_colours_[k.b];
    if (used == ~std::uint64_t{0}) {
      colour_of_[c] = kMaxColours;
      ++overflow_;
      continue;
    }
    const int colour = std::countr_one(used);
    const std::uint64_t bit = std::uint64_t{1} << colour;
    if (k.a_moves) body_colours_[k.a] |= bit;
    if (k.b_moves) body_colours_[k.b] |= bit;
    colour_of_[c] = static_cast<std::uint8_t>(colour);
    ++count[colour];
  }
  // Blocks per colour, in colour order; the colours in use are a prefix (greedy takes the
  // lowest free one).
  colour_first_block_.clear();
  std::uint32_t block = 0;
  for (int colour = 0; colour < kMaxColours && count[colour] > 0; ++colour) {
    colour_first_block_.push_back(block);
    block += (count[colour] + kBlockLanes - 1) / kBlockLanes;
  }
  colour_first_block_.push_back(block);
  const std::size_t blocks = block + overflow_;
  lanes_.assign(blocks * kBlockLanes, kEmptyLane);
  // Fill each colour's lanes in constraint order; overflow constraints one per block.
  const std::size_t colours = colour_first_block_.size() - 1;
  for (std::size_t colour = 0; colour < colours; ++colour) {
    next_lane_[colour] = colour_first_block_[colour] * kBlockLanes;
  }
  std::uint32_t overflow_lane = block * kBlockLanes;
  for (std::size_t c = 0; c < constraints.size(); ++c) {
    const int colour = colour_of_[c];
    if (colour == kMaxColours) {
      lanes_[overflow_lane] = static_cast<std::uint32_t>(c);
      overflow_lane += kBlockLanes;
    } else {
      lanes_[next_lane_[colour]++] = static_cast<std::uint32_t>(c);
    }
  }
}

}  // namespace zonesim::physics
