#include "zone_node/systems/offload_probe.h"

#include <string>

#include "common/log.h"
#include "gpu/default_runtime.h"
#include "gpu/offload_probe.h"
#include "zone_node/systems/flock_backend.h"

namespace zonesim::zone {

void probeZoneThresholds(gpu::OffloadThresholds& t) {
  // Only what zone_node runs on a device: particles, and flocks, which step on the crowd
  // flock or gpu::PlanarFlock (not gpu::Flock), so their own crossover is the boids
  // threshold here. Nothing in a zone uses CrowdBatch: crowd keeps its default.
  t.particles = gpu::crossover(
      gpu::probeWorkload(gpu::Workload::Particles, gpu::defaultRuntime(), gpu::kProbeSizes));
  t.boids = gpu::crossover(probeFlockBackends(gpu::kProbeSizes));
  auto from = [](std::size_t n) {
    return n == gpu::kNeverOffload ? std::string("never") : "from " + std::to_string(n);
  };
  ZS_INFO("offload probe on rank 0: particles %s, zone flocks %s", from(t.particles).c_str(),
          from(t.boids).c_str());
}

}  // namespace zonesim::zone
