#pragma once
// Which rank owns which rectangle of the ground plane. A grid for now; boundaries are
// explicit split positions so that load balancing can move them later.

#include <vector>

#include "common/scene.h"

namespace zonesim::zone {

/// A ground-plane rectangle [min_x, max_x) x [min_z, max_z).
struct ZoneRect {
  double min_x, min_z, max_x, max_z;
  bool contains(double x, double z) const {
    return x >= min_x && x < max_x && z >= min_z && z < max_z;
  }
};

class ZoneLayout {
 public:
  /// A columns x rows grid over the world; rank = row * columns + column.
  ZoneLayout(const SceneBox& world, int columns, int rows);
  /// The scene's grid when it has `ranks` zones, otherwise the most nearly square grid of them.
  static ZoneLayout forRanks(const Scene& scene, int ranks);

  int zoneCount() const { return columns_ * rows_; }
  int columns() const { return columns_; }
  int rows() const { return rows_; }
  ZoneRect rect(int rank) const;
  /// The rank owning a ground-plane point; points outside the world belong to the edge zone.
  int ownerOf(double x, double z) const;

 private:
  int columns_, rows_;
  std::vector<double> x_splits_;  // columns + 1 edges
  std::vector<double> z_splits_;  // rows + 1 edges
};

}  // namespace zonesim::zone
