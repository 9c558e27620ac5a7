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

void ConstraintColouring::buildInOrder(std::span<const ConstraintBodies> constraints,
                                       std::size_t body_count) {
  // last_block_[body] + 1: the first block the body's next constraint may go to (0: none yet).
  last_block_.assign(body_count, 0);
  used_lanes_.clear();
  // free_after_[k]: a block at or after k that may have a free lane (a union-find "next" link
  // over full blocks, so the search skips them).
  free_after_.clear();
  lanes_.clear();
  const auto findFree = [&](std::uint32_t k) {
    std::uint32_t root = k;
    while (root < free_after_.size() && free_after_[root] != root) root = free_after_[root];
    while (k < free_after_.size() && free_after_[k] != k) {
      const std::uint32_t next = free_after_[k];
      free_after_[k] = root;
      k = next;
    }
    return root;
  };
  for (std::size_t c = 0; c < constraints.size(); ++c) {
    const ConstraintBodies& k = constraints[c];
    std::uint32_t first = 0;
    if (k.a_moves) first = std::max(first, last_block_[k.a]);
    if (k.b_moves) first = std::max(first, last_block_[k.b]);
    const std::uint32_t block = findFree(first);
    if (block == used_lanes_.size()) {
      used_lanes_.push_back(0);
      free_after_.push_back(block);
      lanes_.resize(lanes_.size() + kBlockLanes, kEmptyLane);
    }
    lanes_[block * kBlockLanes + used_lanes_[block]] = static_cast<std::uint32_t>(c);
    if (++used_lanes_[block] == kBlockLanes) free_after_[block] = block + 1;
    if (k.a_moves) last_block_[k.a] = block + 1;
    if (k.b_moves) last_block_[k.b] = block + 1;
  }
  colour_first_block_.clear();
  overflow_ = 0;
}

}  // namespace zonesim::physics
