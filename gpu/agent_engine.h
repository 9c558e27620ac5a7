#pragma once
// The storage half shared by the flock's and the crowd batch's engines, one implementation per
// backend: positions and velocities of many agents, uploaded and read back whole. Internal to
// gpu/.

#include <span>
#include <string>
#include <vector>

#include "gpu/particle_types.h"

namespace zonesim::gpu {

class AgentEngine {
 public:
  virtual ~AgentEngine() = default;

  /// Replaces every agent (one upload on a device); both spans have the same length.
  virtual void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) = 0;
  /// Positions in agent order.
  virtual void readPositions(std::vector<Vec3d>& out) = 0;
  /// Velocities in agent order.
  virtual void readVelocities(std::vector<Vec3d>& out) = 0;
  /// Which device holds the agents.
  virtual std::string description() const = 0;
};

}  // namespace zonesim::gpu
