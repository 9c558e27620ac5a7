#include "crowd/flow_field.h"

#include <stdexcept>
#include <utility>

#include "ai/grid_search.h"
#include "crowd/grid_step.h"

namespace zonesim::crowd {

FlowField::FlowField(const ai::GridMap& map, ai::Cell goal)
    : width_(map.width()), height_(map.height()), goal_(goal), map_version_(map.version()) {
  if (!map.passable(goal.x, goal.y)) throw std::invalid_argument("FlowField: goal is blocked");
  ai::GridSearch search(map);
  // The grid is undirected (the same move costs both ways), so distances from the goal are
  // distances to it.
  search.explore(goal, ai::CellRect{0, 0, width_, height_});
  const std::size_t n = std::size_t(width_) * std::size_t(height_);
  distance_.assign(n, -1.0f);
  dir_.assign(n, -1);
  std::vector<double> exact(n, -1.0);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) exact[map.index(x, y)] = search.distanceTo(ai::Cell{x, y});
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      int idx = map.index(x, y);
      distance_[idx] = float(exact[idx]);
      if (exact[idx] <= 0.0) continue;
      // The neighbour through which the shortest path continues: argmin of its distance plus
      // the step, over moves that neither enter a blocked cell nor cut a blocked corner.
      double best = 1e300;
      // The move order (crowd/grid_step.h) fixes the tie-break between equally short steps.
      for (int k = 0; k < 8; ++k) {
        if (!gridStepAllowed(map, ai::Cell{x, y}, k)) continue;
        const ai::Cell n = gridStep(ai::Cell{x, y}, k);
        double d = exact[map.index(n.x, n.y)];
        if (d < 0) continue;
        double through = d + (k >= 4 ? ai::kDiagonalCost : 1.0);
        if (through < best - 1e-9) {
          best = through;
          dir_[idx] = std::int8_t(k);
        }
      }
    }
  chebyshev_bound_ = checkChebyshevBound();
}

FlowField::FlowField(const ai::GridMap& map, ai::Cell goal, std::vector<float> distance,
                     std::vector<std::int8_t> dir)
    : width_(map.width()),
      height_(map.height()),
      goal_(goal),
      map_version_(map.version()),
      distance_(std::move(distance)),
      dir_(std::move(dir)) {
  const std::size_t n = std::size_t(width_) * std::size_t(height_);
  if (distance_.size() != n || dir_.size() != n)
    throw std::invalid_argument("FlowField: fields of the wrong size for the map");
  if (!map.passable(goal.x, goal.y)) throw std::invalid_argument("FlowField: goal is blocked");
  for (std::int8_t k : dir_)
    if (k < -1 || k > 7) throw std::invalid_argument("FlowField: a direction out of range");
  chebyshev_bound_ = checkChebyshevBound();
}

bool FlowField::checkChebyshevBound() const {
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = std::size_t(y) * width_ + x;
      if (dir_[i] < 0) continue;
      const int chebyshev = std::max(std::abs(x - goal_.x), std::abs(y - goal_.y));
      if (!(double(distance_[i]) >= double(chebyshev))) return false;
    }
  return true;
}

void FlowField::setWaypoints(std::vector<float> aims) {
  if (!aims.empty() && aims.size() != 2 * std::size_t(width_) * std::size_t(height_))
    throw std::invalid_argument("FlowField: waypoints of the wrong size for the map");
  waypoints_ = std::move(aims);
}

std::size_t FlowField::bytes() const {
  return distance_.size() * sizeof(float) + dir_.size() * sizeof(std::int8_t) +
         waypoints_.size() * sizeof(float);
}

}  // namespace zonesim::crowd
