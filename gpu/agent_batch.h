#pragma once
// What a Flock and a CrowdBatch share: many agents' positions and velocities held by one
// backend (the double-precision CPU reference, or an OpenCL device in float), replaced whole and
// read back whole. Each adds its own step. No OpenCL or Eigen header comes with it.

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/backend.h"
#include "gpu/particle_types.h"

namespace zonesim::gpu {

class AgentEngine;

class AgentBatch {
 public:
  AgentBatch(AgentBatch&&) noexcept;
  AgentBatch& operator=(AgentBatch&&) noexcept;

  /// Replaces every agent (one upload on OpenCl). Throws std::invalid_argument when the spans
  /// differ in length or hold more than 2^30 agents (the device indexes them in 32 bits).
  void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities);
  /// Agents held.
  std::size_t size() const { return size_; }
  /// Copies the positions into out, in the order given to setAgents (one read-back on OpenCl).
  void readPositions(std::vector<Vec3d>& out) const;
  /// Copies the velocities into out, in the order given to setAgents (one read-back on OpenCl).
  void readVelocities(std::vector<Vec3d>& out) const;
  /// The backend chosen at construction.
  Backend backend() const { return backend_; }
  /// The device that holds and steps the agents.
  std::string deviceDescription() const;

 protected:
  /// Takes the engine of backend; what the agents are called goes into error messages.
  AgentBatch(Backend backend, std::unique_ptr<AgentEngine> engine, const char* agents);
  ~AgentBatch();
  /// The engine given at construction, for the derived class's step.
  AgentEngine& engine() const { return *engine_; }

 private:
  Backend backend_;
  std::size_t size_ = 0;
  std::unique_ptr<AgentEngine> engine_;
  const char* agents_;
};

}  // namespace zonesim::gpu
