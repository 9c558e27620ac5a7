#include "gpu/cpu_boids.h"

#include <algorithm>
#include <cmath>

#include "gpu/boid_grid.h"

namespace zonesim::gpu {
namespace {}  // namespace

CpuBoids::CpuBoids(const GridSpec& grid, const FlockBounds& bounds, const BoidParams& params)
    : grid_(grid), bounds_(bounds), params_(params) {}

void CpuBoids::setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) {
  x_.assign(positions.begin(), positions.end());
  v_.assign(velocities.begin(), velocities.end());
  x_next_.resize(x_.size());
  v_next_.resize(v_.size());
}

void CpuBoids::buildIndex(CellIndex& out) {
  buildCellIndex(grid_, x_, out);
}

// Mirrors boid_step in gpu/kernels/boids.cl line for line, in the same summation order.
void CpuBoids::step(double dt) {
  buildCellIndex(grid_, x_, index_);
  const BoidParams& p = params_;
  const double r = p.perception_radius;
  const std::size_t n = x_.size();
  x_sorted_.resize(n);
  v_sorted_.resize(n);
  for (std::size_t m = 0; m < n; ++m) {
    x_sorted_[m] = x_[index_.order[m]];
    v_sorted_[m] = v_[index_.order[m]];
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t i = index_.order[k];
    const Vec3d xi = x_sorted_[k];
    const Vec3d vi = v_sorted_[k];
    Vec3d separation, offset_sum, velocity_sum;
    std::uint32_t count = 0;
    forEachNeighbour(grid_, index_, x_sorted_, k, r,
                     [&](std::uint32_t m, const Vec3d& d, double d2) {
                       ++count;
                       offset_sum = offset_sum + d;
                       velocity_sum = velocity_sum + v_sorted_[m];
                       if (d2 > 0.0) {
                         double dist = std::sqrt(d2);
                         separation = separation - d * ((r - dist) / (r * dist));
                       }
                     });
    Vec3d acc;
    if (count > 0) {
      double inv = 1.0 / double(count);
      acc = separation * p.separation_weight + (velocity_sum * inv - vi) * p.alignment_weight +
            offset_sum * (inv * p.cohesion_weight);
    }
    Vec3d inside{std::clamp(xi.x, bounds_.min.x, bounds_.max.x),
                 std::clamp(xi.y, bounds_.min.y, bounds_.max.y),
                 std::clamp(xi.z, bounds_.min.z, bounds_.max.z)};
    acc = acc + (inside - xi) * p.bounds_weight;
    Vec3d v = vi + acc * dt;
    double speed = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    if (speed > p.max_speed) {
      v = v * (p.max_speed / speed);
    } else if (speed < p.min_speed && speed > 0.0) {
      v = v * (p.min_speed / speed);
    }
    v_next_[i] = v;
    x_next_[i] = xi + v * dt;
  }
  x_.swap(x_next_);
  v_.swap(v_next_);
}

}  // namespace zonesim::gpu
