#include "zone_node/systems/offload_probe.h"

#include <string>

#include "common/log.h"
#include "gpu/default_runtime.h"
#include "gpu/offload_probe.h"
#include "zone_node/systems/flock_backend.h"

namespace zonesim::zone {

void probeZoneThresholds(gpu::OffloadThresholds& t) {
  // What zone_node runs on a device: particles, and flocks (the crowd flock on the CPU against
  // gpu::PlanarFlock), each at its own crossover.
  t.particles = gpu::crossover(gpu::probeParticles(gpu::defaultRuntime(), gpu::kProbeSizes));
  t.flock = gpu::crossover(probeFlockBackends(gpu::kProbeSizes));
  auto from = [](std::size_t n) {
    return n == gpu::kNeverOffload ? std::string("never") : "from " + std::to_string(n);
  };
  ZS_INFO("offload probe on rank 0: particles %s, zone flocks %s", from(t.particles).c_str(),
          from(t.flock).c_str());
}

}  // namespace zonesim::zone
