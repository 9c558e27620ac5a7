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
    : AgentBatch(backend, makeEngine(backend, bounds, params, std::move(runtime)), "flock") {}

void Flock::step(double dt) {
  if (!std::isfinite(dt) || !(dt > 0.0)) {
    throw std::invalid_argument("flock step dt must be > 0 and finite, not " + std::to_string(dt));
  }
  // AgentBatch holds the BoidEngine made above.
  static_cast<BoidEngine&>(engine()).step(dt);
}

}  // namespace zonesim::gpu
