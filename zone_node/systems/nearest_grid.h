#pragma once
// The nearest of a set of points on the ground plane, within a radius: points bucketed in
// square cells as wide as the widest radius asked, so a query reads 3x3 cells. Agents find the
// nearest enemy with it (agent_senses.cpp), NPCs and avatars the target of a hit or a gift
// (interactions.cpp). The answer depends only on the points, never on the order they were added
// (the lowest id wins a tie), so every decomposition of the world finds the same one.

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace zonesim::zone {

/// `Point` has `id` (ordered, ==), `x` and `z`.
template <typename Point>
class NearestGrid {
 public:
  /// `cell`: at least the widest radius nearest() is asked for.
  explicit NearestGrid(double cell) : cell_(cell) {}
  void add(const Point& p) { cells_[key(cell(p.x), cell(p.z))].push_back(p); }

  /// The nearest point within `radius` of (x, z) that `accept`s, and its distance; the lowest id
  /// on a tie. Null when none.
  template <typename Accept>
  const Point* nearest(double x, double z, double radius, Accept accept, double& dist) const {
    const Point* best = nullptr;
    const std::int64_t cx = cell(x), cz = cell(z);
    // Squared distances skip the points that certainly lose (beyond the radius, or farther
    // than the best so far) with a margin far above their rounding; the rest are compared by
    // hypot exactly as before, so the answer is the same to the bit, just found sooner.
    constexpr double kMargin = 1.0 + 1e-9;
    const double radius2 = radius * radius * kMargin;
    for (std::int64_t i = cx - 1; i <= cx + 1; ++i) {
      for (std::int64_t k = cz - 1; k <= cz + 1; ++k) {
        auto it = cells_.find(key(i, k));
        if (it == cells_.end()) continue;
        for (const Point& p : it->second) {
          const double dx = p.x - x, dz = p.z - z, d2 = dx * dx + dz * dz;
          if (d2 > radius2 || (best && d2 > dist * dist * kMargin)) continue;
          const double d = std::hypot(dx, dz);
          if (d > radius || !accept(p)) continue;
          if (!best || d < dist || (d == dist && p.id < best->id)) {
            best = &p;
            dist = d;
          }
        }
      }
    }
    return best;
  }

 private:
  std::int64_t cell(double v) const { return std::int64_t(std::floor(v / cell_)); }
  static std::int64_t key(std::int64_t x, std::int64_t z) { return x * 4000037 + z; }
  double cell_;
  std::unordered_map<std::int64_t, std::vector<Point>> cells_;  // looked up, never iterated
};

}  // namespace zonesim::zone
