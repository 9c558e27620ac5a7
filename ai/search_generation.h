#pragma once
// Node records that outlive a search carry the generation of the search that last touched
// them (stamp == generation: open, generation + 1: closed), so a new search starts by bumping
// one counter instead of clearing the map's records. Used by A* (GridSearch); jump point search
// keeps 2-byte stamps of its own, apart from its records.

#include <cstdint>
#include <vector>

namespace zonesim::ai {

/// Moves to the next search's pair of stamps; on wrap-around every record is reset once.
template <typename Node>
void nextGeneration(std::uint32_t& generation, std::vector<Node>& nodes) {
  if (generation >= 0xFFFFFFF0u) {
    for (Node& n : nodes) n.stamp = 0;
    generation = 0;
  }
  generation += 2;
}

}  // namespace zonesim::ai
