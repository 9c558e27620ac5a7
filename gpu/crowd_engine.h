#pragma once
// The stepping half of a CrowdBatch, one implementation per backend (the CPU reference in
// crowd_batch.cpp, ClCrowd on a device). Internal to gpu/.

#include <span>

#include "gpu/agent_engine.h"

namespace zonesim::gpu {

class CrowdEngine : public AgentEngine {
 public:
  /// dv = desired - v shortened to max_dv, v += dv, x += v dt for every agent; desired has one
  /// entry per agent (validated by CrowdBatch).
  virtual void step(std::span<const Vec3d> desired, double dt, double max_dv) = 0;
};

}  // namespace zonesim::gpu
