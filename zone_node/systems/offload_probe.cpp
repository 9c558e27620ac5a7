#include "zone_node/systems/offload_probe.h"

#include <string>

#include "common/log.h"
#include "common/scene.h"
#include "gpu/default_runtime.h"
#include "gpu/offload_probe.h"
#include "zone_node/systems/flock_backend.h"

namespace zonesim::zone {

ProbedWorkloads probedWorkloads(const Scene& scene, std::string_view gpu_mode) {
  ProbedWorkloads what;
  bool emitters = false, flocks = false, large_flock = false;
  for (const EmitterPopulation& p : scene.emitters) emitters |= p.count > 0;
  for (const NpcPopulation& p : scene.npcs) {
    flocks |= p.flock.enabled && p.count > 0;
    large_flock |= p.flock.enabled && p.count > 0 && std::size_t(p.count) >= gpu::kProbeSizes[0];
  }
  if (gpu_mode == "probe") what.particles = what.flocks = emitters || flocks;
  if (gpu_mode == "auto") what.flocks = large_flock;
  return what;
}

void probeZoneThresholds(gpu::OffloadThresholds& t, ProbedWorkloads what) {
  auto from = [](std::size_t n) {
    return n == gpu::kNeverOffload ? std::string("never") : "from " + std::to_string(n);
  };
  if (what.particles)
    t.particles = gpu::crossover(gpu::probeParticles(gpu::defaultRuntime(), gpu::kProbeSizes));
  if (what.flocks) t.flock = gpu::crossover(probeFlockBackends(gpu::kProbeSizes));
  if (what.particles)
    ZS_INFO("offload probe on rank 0: particles %s, zone flocks %s", from(t.particles).c_str(),
            from(t.flock).c_str());
  else if (what.flocks)
    ZS_INFO("offload probe on rank 0: zone flocks %s (particles not probed: %s)",
            from(t.flock).c_str(), from(t.particles).c_str());
}

}  // namespace zonesim::zone
