#pragma once
// Which interest cells this gateway reads. Each player needs the cells within its radius (nimbus
// plus a margin ahead of motion); the gateway subscribes to the union, one reader per cell shared
// by refcount. Cyclone cannot change a subscriber's partitions, so a cell entering the union
// means creating its reader and a cell leaving it means deleting it: this class only says which.

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/interest_grid.h"

namespace zonesim::gateway {

/// Cells that entered (refcount 0 -> 1) or left (1 -> 0) the union.
struct CellDelta {
  std::vector<int> added, removed;
  bool empty() const { return added.empty() && removed.empty(); }
};

class InterestManager {
 public:
  /// radius: cells within it are needed; hysteresis: a held cell is kept until it is beyond
  /// radius + hysteresis, so a player pacing along a cell border does not churn readers.
  InterestManager(const InterestGrid& grid, double radius, double hysteresis);

  /// Moves a player's interest to (x, z); union changes are appended to delta. radius > 0
  /// overrides the default radius for this player (its nimbus grew, it moves fast).
  void update(std::uint64_t player, double x, double z, CellDelta& delta, double radius = 0);
  /// Drops a player's interest entirely.
  void remove(std::uint64_t player, CellDelta& delta);
  /// Cells one player holds (empty if unknown), ascending.
  const std::vector<int>& cellsOf(std::uint64_t player) const;
  /// How many players hold a cell.
  int refcount(int cell) const;
  /// Cells in the union.
  std::size_t subscribedCells() const { return refcount_.size(); }
  /// The cells in the union with how many players hold each, ascending by cell (into out).
  void cellsHeld(std::vector<std::pair<int, int>>& out) const;

 private:
  void acquire(int cell, CellDelta& delta);
  void release(int cell, CellDelta& delta);

  InterestGrid grid_;
  double radius_, hysteresis_;
  std::unordered_map<std::uint64_t, std::vector<int>> held_;
  std::unordered_map<int, int> refcount_;
};

}  // namespace zonesim::gateway
