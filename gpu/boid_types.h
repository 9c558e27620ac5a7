#pragma once
// Plain value types of the flock interface: no Eigen, no OpenCL, cheap to include.

#include <cstdint>
#include <vector>

#include "gpu/particle_types.h"

namespace zonesim::gpu {

/// Steering weights and limits shared by both flock backends (see boids.cl for the rules).
struct BoidParams {
  double perception_radius = 2.0;  ///< Metres, > 0; neighbours are strictly closer than this.
  double separation_weight = 1.5;  ///< Push away from close neighbours, 1/s^2 per unit push.
  double alignment_weight = 1.0;   ///< Pull toward the neighbours' mean velocity, 1/s.
  double cohesion_weight = 0.5;    ///< Pull toward the neighbours' centre, 1/s^2.
  double bounds_weight = 1.0;      ///< Pull back into the bounds when outside, 1/s^2.
  double min_speed = 0.5;          ///< Metres per second, >= 0; slower boids are sped up.
  double max_speed = 5.0;          ///< Metres per second, >= min_speed.
};

/// The box the flock lives in; the neighbour grid covers it with cubic cells of the
/// perception radius. Boids outside count in the border cells (still correct, only slower).
struct FlockBounds {
  Vec3d min{-50, 0, -50};  ///< Lowest corner.
  Vec3d max{50, 50, 50};   ///< Highest corner, above min on every axis.
};

/// The uniform grid derived from bounds and the perception radius.
struct GridSpec {
  Vec3d origin;          ///< The bounds' lowest corner.
  double cell = 1;       ///< Cell edge, equal to the perception radius.
  std::uint32_t nx = 1;  ///< Cells along x.
  std::uint32_t ny = 1;  ///< Cells along y.
  std::uint32_t nz = 1;  ///< Cells along z.
  /// Total cells.
  std::uint32_t cells() const { return nx * ny * nz; }
};

/// The neighbour search's index: agents sorted by cell and each cell's range in that order.
struct CellIndex {
  std::vector<std::uint32_t> order;       ///< Agent ids sorted by (cell, id).
  std::vector<std::uint32_t> cell_start;  ///< First position in order per cell.
  std::vector<std::uint32_t> cell_end;    ///< One past the last; equal to start when empty.
};

}  // namespace zonesim::gpu
