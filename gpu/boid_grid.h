#pragma once
// The uniform grid both flock backends use for their neighbour search, on the host side: its
// shape from the bounds, the cell of a position, and the 27-cell query. Internal to gpu/.

#include <cstdint>
#include <span>
#include <vector>

#include "gpu/boid_types.h"

namespace zonesim::gpu {

/// Most cells a grid may have: the device keeps two uint arrays of this length.
inline constexpr std::uint32_t kMaxGridCells = 1u << 24;

/// Validates bounds and params and derives the grid; throws std::invalid_argument naming the
/// bad value (non-finite, empty box, radius <= 0, speeds out of order, too many cells).
GridSpec makeGrid(const FlockBounds& bounds, const BoidParams& params);

/// The cell of one grid coordinate: floor((x - origin) / cell), clamped into [0, n - 1].
/// Clamping keeps the 27-cell search exact: it never moves two points more than one cell apart.
std::uint32_t cellCoordinate(double x, double origin, double cell, std::uint32_t n);

/// The linear cell id of a position: (cz * ny + cy) * nx + cx.
std::uint32_t cellOf(const GridSpec& grid, const Vec3d& p);

/// Builds the index by a counting sort (stable, so ids ascend within a cell, as on the device).
void buildCellIndex(const GridSpec& grid, std::span<const Vec3d> positions, CellIndex& out);

/// Calls visit(m, d, d2) for every slot m != k of the sorted arrays whose position is strictly
/// within radius of slot k's, where sorted[m] = positions[index.order[m]], d is sorted[m] -
/// sorted[k] and d2 its squared length. The visiting order is the sum order of boids.cl: cells
/// by z, y, x from the lowest, slots (so ids) ascending within a cell. Sorted copies keep a
/// cell's boids together in memory; reading them through order instead is several times slower
/// once the flock outgrows the caches.
template <typename Visit>
void forEachNeighbour(const GridSpec& grid, const CellIndex& index, std::span<const Vec3d> sorted,
                      std::uint32_t k, double radius, Visit&& visit) {
  const Vec3d p = sorted[k];
  const std::uint32_t cx = cellCoordinate(p.x, grid.origin.x, grid.cell, grid.nx);
  const std::uint32_t cy = cellCoordinate(p.y, grid.origin.y, grid.cell, grid.ny);
  const std::uint32_t cz = cellCoordinate(p.z, grid.origin.z, grid.cell, grid.nz);
  const double r2 = radius * radius;
  const std::uint32_t z1 = cz + 1 < grid.nz ? cz + 1 : cz;
  const std::uint32_t y1 = cy + 1 < grid.ny ? cy + 1 : cy;
  const std::uint32_t x1 = cx + 1 < grid.nx ? cx + 1 : cx;
  for (std::uint32_t z = cz > 0 ? cz - 1 : 0; z <= z1; ++z) {
    for (std::uint32_t y = cy > 0 ? cy - 1 : 0; y <= y1; ++y) {
      for (std::uint32_t x = cx > 0 ? cx - 1 : 0; x <= x1; ++x) {
        const std::uint32_t cell = (z * grid.ny + y) * grid.nx + x;
        for (std::uint32_t m = index.cell_start[cell]; m < index.cell_end[cell]; ++m) {
          if (m == k) continue;
          const Vec3d d{sorted[m].x - p.x, sorted[m].y - p.y, sorted[m].z - p.z};
          const double d2 = d.x * d.x + d.y * d.y + d.z * d.z;
          if (d2 < r2) visit(m, d, d2);
        }
      }
    }
  }
}

/// Ids of the agents strictly within radius of agent i (i excluded), in the grid's visiting
/// order (see forEachNeighbour); for tests, so it allocates freely.
void gridNeighbours(const GridSpec& grid, const CellIndex& index, std::span<const Vec3d> positions,
                    std::uint32_t i, double radius, std::vector<std::uint32_t>& out);

}  // namespace zonesim::gpu
