#pragma once
// The interest-cell grid: a fixed uniform grid over the ground plane (x-z), independent of
// zones. Cell (ix, iz) has id iz * columns + ix and is DDS partition "c.<ix>.<iz>".

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/scene_geometry.h"

namespace zonesim {

class InterestGrid {
 public:
  InterestGrid(const SceneBox& world, double cell_size)
      : min_x_(world.min.x),
        min_z_(world.min.z),
        cell_size_(cell_size),
        columns_(std::max(1, int(std::ceil((world.max.x - world.min.x) / cell_size)))),
        rows_(std::max(1, int(std::ceil((world.max.z - world.min.z) / cell_size)))) {}

  int columns() const { return columns_; }
  int rows() const { return rows_; }
  int cellCount() const { return columns_ * rows_; }
  double cell_size() const { return cell_size_; }

  int columnOf(double x) const { return clampedIndex((x - min_x_) / cell_size_, columns_); }
  int rowOf(double z) const { return clampedIndex((z - min_z_) / cell_size_, rows_); }
  /// Cell id of a ground-plane point (clamped into the grid).
  int cellOf(double x, double z) const { return rowOf(z) * columns_ + columnOf(x); }
  int columnOfCell(int cell) const { return cell % columns_; }
  int rowOfCell(int cell) const { return cell / columns_; }

  /// Cells whose square meets the disc of radius r around (x, z), touching included, in id order.
  std::vector<int> cellsWithin(double x, double z, double r) const {
    std::vector<int> out;
    cellsWithin(x, z, r, out);
    return out;
  }
  /// The same into `out` (cleared first): no allocation once its capacity suffices.
  void cellsWithin(double x, double z, double r, std::vector<int>& out) const {
    out.clear();
    // One cell of slack each way: a disc that just touches a cell's lower edge floors to the
    // next cell; the distance test below decides.
    int c0 = std::max(columnOf(x - r) - 1, 0), c1 = std::min(columnOf(x + r) + 1, columns_ - 1);
    int r0 = std::max(rowOf(z - r) - 1, 0), r1 = std::min(rowOf(z + r) + 1, rows_ - 1);
    for (int iz = r0; iz <= r1; ++iz)
      for (int ix = c0; ix <= c1; ++ix) {
        double cx = std::clamp(x, min_x_ + ix * cell_size_, min_x_ + (ix + 1) * cell_size_);
        double cz = std::clamp(z, min_z_ + iz * cell_size_, min_z_ + (iz + 1) * cell_size_);
        if ((cx - x) * (cx - x) + (cz - z) * (cz - z) <= r * r) out.push_back(iz * columns_ + ix);
      }
  }

 private:
  // Clamped in floating point before converting: huge, infinite or NaN coordinates of a
  // runaway entity must not overflow the int conversion (NaN goes to cell 0).
  static int clampedIndex(double cells, int count) {
    double i = std::floor(cells);
    return i >= count - 1 ? count - 1 : (i > 0 ? int(i) : 0);
  }

  double min_x_, min_z_, cell_size_;
  int columns_, rows_;
};

}  // namespace zonesim
