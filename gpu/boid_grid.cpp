#include "gpu/boid_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace zonesim::gpu {
namespace {

bool finite(const Vec3d& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::uint32_t cellsAlong(double lo, double hi, double cell) {
  return static_cast<std::uint32_t>(std::max(1.0, std::ceil((hi - lo) / cell)));
}

}  // namespace

GridSpec makeGrid(const FlockBounds& bounds, const BoidParams& params) {
  if (!finite(bounds.min) || !finite(bounds.max) || !(bounds.max.x > bounds.min.x) ||
      !(bounds.max.y > bounds.min.y) || !(bounds.max.z > bounds.min.z)) {
    throw std::invalid_argument("flock bounds must be finite with max above min on every axis");
  }
  const double r = params.perception_radius;
  if (!std::isfinite(r) || !(r > 0.0)) {
    throw std::invalid_argument("flock perception radius must be > 0, not " + std::to_string(r));
  }
  for (double w : {params.separation_weight, params.alignment_weight, params.cohesion_weight,
                   params.bounds_weight}) {
    if (!std::isfinite(w)) throw std::invalid_argument("flock weights must be finite");
  }
  if (!(params.min_speed >= 0.0) || !(params.max_speed >= params.min_speed) ||
      !std::isfinite(params.max_speed)) {
    throw std::invalid_argument("flock speeds need 0 <= min_speed <= max_speed, finite");
  }
  // The count is checked in double before it could overflow 32 bits.
  double cells = std::ceil((bounds.max.x - bounds.min.x) / r) *
                 std::ceil((bounds.max.y - bounds.min.y) / r) *
                 std::ceil((bounds.max.z - bounds.min.z) / r);
  if (cells > kMaxGridCells) {
    throw std::invalid_argument("flock grid would have " + std::to_string(cells) +
                                " cells, more than " + std::to_string(kMaxGridCells) +
                                ": shrink the bounds or raise the perception radius");
  }
  return GridSpec{bounds.min, r, cellsAlong(bounds.min.x, bounds.max.x, r),
                  cellsAlong(bounds.min.y, bounds.max.y, r),
                  cellsAlong(bounds.min.z, bounds.max.z, r)};
}

std::uint32_t cellCoordinate(double x, double origin, double cell, std::uint32_t n) {
  double c = std::floor((x - origin) / cell);
  if (!(c > 0.0)) return 0;  // also NaN, so that a bad value cannot index out of the grid
  return c >= double(n - 1) ? n - 1 : static_cast<std::uint32_t>(c);
}

std::uint32_t cellOf(const GridSpec& grid, const Vec3d& p) {
  std::uint32_t cx = cellCoordinate(p.x, grid.origin.x, grid.cell, grid.nx);
  std::uint32_t cy = cellCoordinate(p.y, grid.origin.y, grid.cell, grid.ny);
  std::uint32_t cz = cellCoordinate(p.z, grid.origin.z, grid.cell, grid.nz);
  return (cz * grid.ny + cy) * grid.nx + cx;
}

void buildCellIndex(const GridSpec& grid, std::span<const Vec3d> positions, CellIndex& out) {
  const std::uint32_t cells = grid.cells();
  out.cell_start.assign(cells, 0);
  out.cell_end.assign(cells, 0);
  out.order.resize(positions.size());
  // cell_end counts first, then becomes each cell's fill cursor and ends as its end.
  for (const Vec3d& p : positions) ++out.cell_end[cellOf(grid, p)];
  std::uint32_t sum = 0;
  for (std::uint32_t c = 0; c < cells; ++c) {
    out.cell_start[c] = sum;
    sum += out.cell_end[c];
    out.cell_end[c] = out.cell_start[c];
  }
  for (std::uint32_t i = 0; i < positions.size(); ++i) {
    out.order[out.cell_end[cellOf(grid, positions[i])]++] = i;
  }
}

void gridNeighbours(const GridSpec& grid, const CellIndex& index, std::span<const Vec3d> positions,
                    std::uint32_t i, double radius, std::vector<std::uint32_t>& out) {
  out.clear();
  std::vector<Vec3d> sorted(positions.size());
  std::uint32_t slot = 0;
  for (std::uint32_t m = 0; m < positions.size(); ++m) {
    sorted[m] = positions[index.order[m]];
    if (index.order[m] == i) slot = m;
  }
  forEachNeighbour(grid, index, sorted, slot, radius,
                   [&](std::uint32_t m, const Vec3d&, double) { out.push_back(index.order[m]); });
}

}  // namespace zonesim::gpu
