#pragma once
// Large flocks (birds, fish, bats) steered by separation, alignment and cohesion over a uniform
// neighbour grid, either by the double-precision CPU reference or on an OpenCL device in float.
// No OpenCL or Eigen header comes with it.

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/backend.h"
#include "gpu/boid_types.h"

namespace zonesim::gpu {

class BoidEngine;
class ClRuntime;

class Flock {
 public:
  /// Validates bounds and params (std::invalid_argument naming the bad value). OpenCl uses
  /// runtime, else the process's default device; throws NoDeviceError without one.
  Flock(Backend backend, const FlockBounds& bounds, const BoidParams& params,
        std::shared_ptr<ClRuntime> runtime = nullptr);
  ~Flock();
  Flock(Flock&&) noexcept;
  Flock& operator=(Flock&&) noexcept;

  /// Replaces every boid (one upload on OpenCl); the spans must have the same length.
  void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities);
  /// Advances every boid by dt seconds (> 0, finite): grid, steering, bounded speed, move.
  void step(double dt);

  /// Boids in the flock.
  std::size_t size() const { return size_; }
  /// Copies the positions into out, in the order given to setAgents (one read-back on OpenCl).
  void readPositions(std::vector<Vec3d>& out) const;
  /// Copies the velocities into out, in the order given to setAgents.
  void readVelocities(std::vector<Vec3d>& out) const;
  /// The backend chosen at construction.
  Backend backend() const { return backend_; }
  /// The device that steps the flock.
  std::string deviceDescription() const;

 private:
  Backend backend_;
  std::size_t size_ = 0;
  std::unique_ptr<BoidEngine> engine_;
};

}  // namespace zonesim::gpu
