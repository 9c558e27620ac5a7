#include "gpu/agent_batch.h"

#include <stdexcept>
#include <string>

#include "gpu/agent_engine.h"

namespace zonesim::gpu {

AgentBatch::AgentBatch(Backend backend, std::unique_ptr<AgentEngine> engine, const char* agents)
    : backend_(backend), engine_(std::move(engine)), agents_(agents) {}

AgentBatch::~AgentBatch() = default;
AgentBatch::AgentBatch(AgentBatch&&) noexcept = default;
AgentBatch& AgentBatch::operator=(AgentBatch&&) noexcept = default;

void AgentBatch::setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) {
  if (positions.size() != velocities.size()) {
    throw std::invalid_argument(std::string(agents_) +
                                " positions and velocities differ in length");
  }
  // The device indexes agents with 32-bit ids (and the flock pads its sort to a power of two).
  if (positions.size() > (std::size_t(1) << 30)) {
    throw std::invalid_argument(std::string(agents_) + " of " + std::to_string(positions.size()) +
                                " agents is beyond 2^30");
  }
  engine_->setAgents(positions, velocities);
  size_ = positions.size();
}

void AgentBatch::readPositions(std::vector<Vec3d>& out) const {
  engine_->readPositions(out);
}

void AgentBatch::readVelocities(std::vector<Vec3d>& out) const {
  engine_->readVelocities(out);
}

std::string AgentBatch::deviceDescription() const {
  return engine_->description();
}

}  // namespace zonesim::gpu
