#include "ai/landmark_heuristic.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "ai/grid_search.h"

namespace zonesim::ai {

namespace {

/// The cells of the largest connected passable area. Without corner cutting a diagonal step
/// needs both cells beside it open, so 8-connected areas are the 4-connected ones.
std::vector<int> largestArea(const GridMap& map) {
  std::vector<char> seen(std::size_t(map.width()) * std::size_t(map.height()), 0);
  std::vector<int> best, area, queue;
  for (int start = 0; start < int(seen.size()); ++start) {
    if (seen[std::size_t(start)] || !map.passableAt(start)) continue;
    area.clear();
    queue.assign(1, start);
    seen[std::size_t(start)] = 1;
    while (!queue.empty()) {
      const int at = queue.back();
      queue.pop_back();
      area.push_back(at);
      const Cell c = map.cellAt(at);
      const Cell next[4] = {{c.x + 1, c.y}, {c.x - 1, c.y}, {c.x, c.y + 1}, {c.x, c.y - 1}};
      for (const Cell& n : next) {
        if (!map.passable(n.x, n.y)) continue;
        const int i = map.index(n.x, n.y);
        if (seen[std::size_t(i)]) continue;
        seen[std::size_t(i)] = 1;
        queue.push_back(i);
      }
    }
    if (area.size() > best.size()) best.swap(area);
  }
  return best;
}

}  // namespace

LandmarkHeuristic::LandmarkHeuristic(const GridMap& map, int count)
    : map_(&map), width_(map.width()), height_(map.height()), version_(map.version()) {
  if (count < 1 || count > kMaxLandmarks)
    throw std::invalid_argument("landmark count " + std::to_string(count) +
                                " is out of range (1 to " + std::to_string(kMaxLandmarks) + ")");
  const std::vector<int> area = largestArea(map);
  count_ = std::min<int>(count, int(area.size()));
  costs_.assign(std::size_t(width_) * std::size_t(height_) * std::size_t(count_), -1);
  if (count_ == 0) return;

  GridSearch dijkstra(map);
  const CellRect whole{0, 0, width_, height_};
  // Farthest first: `nearest` is each area cell's cost to the closest landmark chosen so far
  // (to the seed before the first), and the next landmark is the cell where it is largest.
  std::vector<std::int64_t> nearest(area.size(), INT64_MAX);
  Cell from = map.cellAt(area.front());
  for (int l = -1; l < count_; ++l) {
    dijkstra.explore(from, whole);
    std::size_t far = 0;
    for (std::size_t i = 0; i < area.size(); ++i) {
      const std::int64_t d = dijkstra.costTo(map.cellAt(area[i]));
      if (l >= 0) costs_[std::size_t(area[i]) * std::size_t(count_) + std::size_t(l)] = d;
      nearest[i] = std::min(nearest[i], d);
      if (nearest[i] > nearest[far]) far = i;
    }
    if (l == -1) nearest.assign(area.size(), INT64_MAX);  // the seed is not a landmark
    if (l >= 0) landmarks_.push_back(from);
    from = map.cellAt(area[far]);
  }
}

void LandmarkHeuristic::prepareGoal(int x, int y, Goal& goal) const {
  goal.landmark.clear();
  goal.cost.clear();
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const std::int64_t* row = &costs_[std::size_t(y * width_ + x) * std::size_t(count_)];
  for (int l = 0; l < count_; ++l) {
    if (row[l] < 0) continue;
    goal.landmark.push_back(l);
    goal.cost.push_back(row[l]);
  }
}

}  // namespace zonesim::ai
