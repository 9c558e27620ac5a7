#pragma once
// The storage and stepping half of a Flock, one implementation per backend. Called once per
// step or batch, never per agent. Internal to gpu/.

#include <span>
#include <string>
#include <vector>

#include "gpu/boid_types.h"

namespace zonesim::gpu {

class BoidEngine {
 public:
  virtual ~BoidEngine() = default;

  /// Replaces the flock (one upload on a device); both spans have the same length.
  virtual void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) = 0;
  /// Rebuilds the neighbour grid from the current positions and advances every boid by dt.
  virtual void step(double dt) = 0;
  /// Positions in agent order.
  virtual void readPositions(std::vector<Vec3d>& out) = 0;
  /// Velocities in agent order.
  virtual void readVelocities(std::vector<Vec3d>& out) = 0;
  /// Builds the grid from the current positions without stepping and returns it, for tests.
  virtual void buildIndex(CellIndex& out) = 0;
  /// Which device runs the flock.
  virtual std::string description() const = 0;
};

}  // namespace zonesim::gpu
