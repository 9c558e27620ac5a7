#pragma once
// Overlap between agents' bodies, a crowd criterion that steering libraries do not publish:
// agents are discs of one radius, and two whose centres are closer than twice it overlap by
// the difference. Measured over the neighbour grid a step has built, so a measurement costs a
// query per agent and no build.

#include <cstddef>
#include <cstdint>

#include "crowd/neighbour_grid.h"

namespace zonesim::crowd {

/// The deepest overlap among the agents of a grid, and how many pairs overlap.
struct Overlap {
  double depth = 0.0;          ///< 2 radius - centre distance of the closest pair; 0 if none
  std::uint64_t a = 0, b = 0;  ///< ids of the closest overlapping pair (a < b); 0 if none
  std::size_t pairs = 0;       ///< pairs closer than 2 radius
  Vec2 at;                     ///< midpoint of the closest overlapping pair
};

/// Overlap of discs of `radius` (> 0) around the grid's entries: every pair of owned entries,
/// and every owned entry with a ghost (ghost pairs belong to their owner rank), counted once.
Overlap deepestOverlap(const NeighbourGrid& grid, double radius);

}  // namespace zonesim::crowd
