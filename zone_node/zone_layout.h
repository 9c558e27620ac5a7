#pragma once
// Which rank owns which rectangle of the ground plane. Columns split the world along x; each
// column is split along z into rows of its own, so boundaries can move independently: at start
// (recursive coordinate bisection by entity count) and at run time (load balancing by measured
// cost). Ranks are numbered row * columns + column.

#include <algorithm>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "common/scene_geometry.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// A ground-plane rectangle [min_x, max_x) x [min_z, max_z).
struct ZoneRect {
  double min_x, min_z, max_x, max_z;
  bool contains(double x, double z) const {
    return x >= min_x && x < max_x && z >= min_z && z < max_z;
  }
  double area() const { return (max_x - min_x) * (max_z - min_z); }
  /// Distance on the ground plane from (x, z) to the rectangle (0 inside).
  double distanceTo(double x, double z) const {
    double dx = std::max({min_x - x, 0.0, x - max_x});
    double dz = std::max({min_z - z, 0.0, z - max_z});
    return std::sqrt(dx * dx + dz * dz);
  }
};

class ZoneLayout {
 public:
  /// An even columns x rows grid over the world.
  ZoneLayout(const SceneBox& world, int columns, int rows);
  /// The scene's grid when it has `ranks` zones, otherwise the most nearly square grid of them;
  /// with layout rcb, boundaries placed by bisection of the initial entity positions.
  static ZoneLayout forRanks(const Scene& scene, int ranks);

  int zoneCount() const { return columns_ * rows_; }
  int columns() const { return columns_; }
  int rows() const { return rows_; }
  ZoneRect rect(int rank) const;
  /// The rank owning a ground-plane point; points outside the world belong to the edge zone.
  int ownerOf(double x, double z) const;

  /// Places boundaries so each zone holds an equal share of the points (x, z): columns by x
  /// quantiles, then rows by z quantiles of the points in each column.
  void bisect(std::span<const std::pair<double, double>> points);
  /// Moves boundaries `step` (0..1] of the way toward equal cost per zone, cost[r] being rank
  /// r's measured cost, taken as spread evenly over its rectangle. No zone becomes narrower
  /// than min_width on either axis.
  void rebalance(std::span<const double> cost, double step, double min_width);

 private:
  int columns_, rows_;
  std::vector<double> x_splits_;               // columns + 1 edges
  std::vector<std::vector<double>> z_splits_;  // per column: rows + 1 edges
};

}  // namespace zonesim::zone
