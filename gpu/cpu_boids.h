#pragma once
// The CPU flock: the same rules and grid as gpu/kernels/boids.cl in double precision. It is the
// reference the OpenCL path is tested against, and the faster choice for small flocks.

#include <vector>

#include "gpu/boid_engine.h"

namespace zonesim::gpu {

class CpuBoids final : public BoidEngine {
 public:
  /// A flock in grid with params (both validated by makeGrid).
  CpuBoids(const GridSpec& grid, const FlockBounds& bounds, const BoidParams& params);

  void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) override;
  void step(double dt) override;
  void readPositions(std::vector<Vec3d>& out) override { out = x_; }
  void readVelocities(std::vector<Vec3d>& out) override { out = v_; }
  void buildIndex(CellIndex& out) override;
  std::string description() const override { return "CPU reference (double precision)"; }

 private:
  GridSpec grid_;
  FlockBounds bounds_;
  BoidParams params_;
  // Double-buffered: every boid reads the old state, so the step does not depend on order.
  std::vector<Vec3d> x_, v_, x_next_, v_next_;
  // x_ and v_ in grid order, rebuilt every step (see forEachNeighbour).
  std::vector<Vec3d> x_sorted_, v_sorted_;
  CellIndex index_;
};

}  // namespace zonesim::gpu
