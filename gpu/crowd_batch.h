#pragma once
// Batch integration of many crowd agents (the semi-implicit Euler step toward each agent's
// desired velocity, with bounded acceleration), either by the double-precision CPU reference or
// on an OpenCL device in float. No OpenCL or Eigen header comes with it.

#include <memory>
#include <span>

#include "gpu/agent_batch.h"

namespace zonesim::gpu {

class ClRuntime;

class CrowdBatch : public AgentBatch {
 public:
  /// OpenCl uses runtime, else the process's default device; throws NoDeviceError without one.
  explicit CrowdBatch(Backend backend, std::shared_ptr<ClRuntime> runtime = nullptr);

  /// One step for every agent: dv = desired - v clamped to max_acceleration * dt in length,
  /// v += dv, x += v dt. desired has one entry per agent (one upload on OpenCl). Throws
  /// std::invalid_argument unless dt > 0 and max_acceleration >= 0, both finite.
  void step(std::span<const Vec3d> desired, double dt, double max_acceleration);
  // setAgents, size, readPositions, readVelocities, backend, deviceDescription: AgentBatch.
};

}  // namespace zonesim::gpu
