#pragma once
// Large flocks (birds, fish, bats) steered by separation, alignment and cohesion over a uniform
// neighbour grid, either by the double-precision CPU reference or on an OpenCL device in float.
// No OpenCL or Eigen header comes with it.

#include <memory>

#include "gpu/agent_batch.h"
#include "gpu/boid_types.h"

namespace zonesim::gpu {

class BoidEngine;
class ClRuntime;

class Flock : public AgentBatch {
 public:
  /// Validates bounds and params (std::invalid_argument naming the bad value). OpenCl uses
  /// runtime, else the process's default device; throws NoDeviceError without one.
  Flock(Backend backend, const FlockBounds& bounds, const BoidParams& params,
        std::shared_ptr<ClRuntime> runtime = nullptr);

  /// Advances every boid by dt seconds (> 0, finite): grid, steering, bounded speed, move.
  void step(double dt);
  // setAgents, size, readPositions, readVelocities, backend, deviceDescription: AgentBatch.
};

}  // namespace zonesim::gpu
