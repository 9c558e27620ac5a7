#pragma once
// The storage and stepping half of a Flock, one implementation per backend. Called once per
// step or batch, never per agent. Internal to gpu/.

#include "gpu/agent_engine.h"
#include "gpu/boid_types.h"

namespace zonesim::gpu {

class BoidEngine : public AgentEngine {
 public:
  /// Rebuilds the neighbour grid from the current positions and advances every boid by dt.
  virtual void step(double dt) = 0;
  /// Builds the grid from the current positions without stepping and returns it, for tests.
  virtual void buildIndex(CellIndex& out) = 0;
};

}  // namespace zonesim::gpu
