#pragma once
// A flow field toward one destination (the seed's "embedded map data"): the integration field
// (exact 8-connected octile distance to the goal without corner cutting, by Dijkstra from the
// goal with ai::GridSearch) and, per cell, the neighbour to step to next. Built once per
// destination and shared read-only by every agent heading there; looking up an agent's next
// cell is one array read, whatever the number of agents.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "ai/grid_map.h"
#include "crowd/grid_step.h"

namespace zonesim::crowd {

/// Integration and direction fields toward one goal cell of a map.
class FlowField {
 public:
  /// Builds both fields for `goal` (a passable cell) on `map` as it is now.
  FlowField(const ai::GridMap& map, ai::Cell goal);
  /// Fields built earlier for `goal` on this map (crowd/flow_field_file.h reads them), taken
  /// as they are. Throws std::invalid_argument when the sizes do not fit the map or a direction
  /// is out of range.
  FlowField(const ai::GridMap& map, ai::Cell goal, std::vector<float> distance,
            std::vector<std::int8_t> dir);

  /// The destination cell.
  ai::Cell goal() const { return goal_; }
  /// Octile path length from `c` to the goal; negative when unreachable or off the map.
  double distance(ai::Cell c) const {
    if (c.x < 0 || c.y < 0 || c.x >= width_ || c.y >= height_) return -1.0;
    return distance_[std::size_t(c.y) * width_ + c.x];
  }
  /// The next cell on a shortest path from `c`; false at the goal or where unreachable.
  bool next(ai::Cell c, ai::Cell& out) const {
    if (c.x < 0 || c.y < 0 || c.x >= width_ || c.y >= height_) return false;
    const int k = dir_[std::size_t(c.y) * width_ + c.x];
    if (k < 0) return false;
    out = gridStep(c, k);
    return true;
  }
  /// Starts loading the whole direction field into the cache (a prefetch per line).
  void prefetchDirections() const {
    for (std::size_t i = 0; i < dir_.size(); i += kCacheLine) __builtin_prefetch(dir_.data() + i);
  }
  /// Cache lines that prefetchDirections() loads.
  std::size_t directionLines() const { return (dir_.size() + kCacheLine - 1) / kCacheLine; }
  /// For a cell with a next cell: a lower bound on distance(c) that reads no field memory,
  /// the Chebyshev distance to the goal (no 8-connected path is shorter); 0 for a loaded field
  /// that breaks it. A crowd asks it first and reads the distance only near the goal.
  double nextCellLowerBound(ai::Cell c) const {
    if (!chebyshev_bound_) return 0.0;
    return double(std::max(std::abs(c.x - goal_.x), std::abs(c.y - goal_.y)));
  }
  /// The map version the fields were built from (rebuild when the map's version differs).
  std::uint64_t mapVersion() const { return map_version_; }
  /// Memory held by the fields, in bytes.
  std::size_t bytes() const;
  /// The integration field, row by row (negative: unreachable).
  const std::vector<float>& distances() const { return distance_; }
  /// The direction field, row by row (0..7 into the grid steps, -1 at the goal or unreachable).
  const std::vector<std::int8_t>& directions() const { return dir_; }

  /// Any-angle aims for this goal (crowd/flow_waypoints.h: two floats per cell, NaN where
  /// none); empty: none. Throws std::invalid_argument when the size does not fit the map.
  void setWaypoints(std::vector<float> aims);
  /// Whether the field carries aims.
  bool hasWaypoints() const { return !waypoints_.empty(); }
  /// The aim of cell `c` in map units (a cell covers [x, x+1)); false where it has none.
  bool waypoint(ai::Cell c, double& x, double& y) const {
    if (c.x < 0 || c.y < 0 || c.x >= width_ || c.y >= height_) return false;
    const std::size_t at = 2 * (std::size_t(c.y) * std::size_t(width_) + std::size_t(c.x));
    if (std::isnan(waypoints_[at])) return false;
    x = waypoints_[at];
    y = waypoints_[at + 1];
    return true;
  }

 private:
  static constexpr std::size_t kCacheLine = 64;
  int width_ = 0, height_ = 0;
  ai::Cell goal_;
  std::uint64_t map_version_ = 0;
  std::vector<float> distance_;   // float: 24 bits cover paths of millions of cells to 0.1
  std::vector<std::int8_t> dir_;  // 0..7 into kNeighbourSteps, -1 at the goal or unreachable
  std::vector<float> waypoints_;  // x, y per cell (map units), NaN where none; empty: none
  // Every cell with a direction lies at least its Chebyshev distance from the goal (checked
  // once; see nextCellLowerBound).
  bool chebyshev_bound_ = false;

  bool checkChebyshevBound() const;
};

}  // namespace zonesim::crowd
