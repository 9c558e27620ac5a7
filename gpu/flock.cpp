#include "gpu/flock.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "gpu/boid_grid.h"
#include "gpu/cl_boids.h"
#include "gpu/cpu_boids.h"
#include "gpu/default_runtime.h"

namespace zonesim::gpu {
namespace {

std::unique_ptr<BoidEngine> makeEngine(Backend backend, const FlockBounds& bounds,
                                       const BoidParams& params,
                                       std::shared_ptr<ClRuntime> runtime) {
  GridSpec grid = makeGrid(bounds, params);
  if (backend == Backend::Cpu) return std::make_unique<CpuBoids>(grid, bounds, params);
  if (!runtime) runtime = defaultRuntime();
  return std::make_unique<ClBoids>(std::move(runtime), grid, bounds, params);
}

}  // namespace

Flock::Flock(Backend backend, const FlockBounds& bounds, const BoidParams& params,
             std::shared_ptr<ClRuntime> runtime)
    : backend_(backend), engine_(makeEngine(backend, bounds, params, std::move(runtime))) {}

Flock::~Flock() = default;
Flock::Flock(Flock&&) noexcept = default;
Flock& Flock::operator=(Flock&&) noexcept = default;

void Flock::setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) {
  if (positions.size() != velocities.size()) {
    throw std::invalid_argument("flock positions and velocities differ in length");
  }
  // The device indexes boids with 32-bit ids and pads the sort to the next power of two.
  if (positions.size() > (std::size_t(1) << 30)) {
    throw std::invalid_argument("flock of " + std::to_string(positions.size()) +
                                " boids is beyond 2^30");
  }
  engine_->setAgents(positions, velocities);
  size_ = positions.size();
}

void Flock::step(double dt) {
  if (!std::isfinite(dt) || !(dt > 0.0)) {
    throw std::invalid_argument("flock step dt must be > 0 and finite, not " + std::to_string(dt));
  }
  engine_->step(dt);
}

void Flock::readPositions(std::vector<Vec3d>& out) const {
  engine_->readPositions(out);
}

void Flock::readVelocities(std::vector<Vec3d>& out) const {
  engine_->readVelocities(out);
}

std::string Flock::deviceDescription() const {
  return engine_->description();
}

}  // namespace zonesim::gpu
