#include "gpu/offload_probe.h"

#include "gpu/workload_scene.h"

namespace zonesim::gpu {
namespace {

// Enough ticks to average out a scheduler slice, few enough to keep start-up short.
constexpr int kProbeSteps = 3;
constexpr int kProbeRepeats = 2;

}  // namespace

std::vector<ProbeSample> probeParticles(std::shared_ptr<ClRuntime> runtime,
                                        std::span<const std::size_t> sizes) {
  std::vector<ProbeSample> samples;
  for (std::size_t n : sizes) {
    ParticleWorkload cpu(Backend::Cpu, n);
    ParticleWorkload device(Backend::OpenCl, n, runtime);
    samples.push_back({n, secondsPerTick(cpu, kProbeSteps, kProbeRepeats),
                       secondsPerTick(device, kProbeSteps, kProbeRepeats)});
  }
  return samples;
}

}  // namespace zonesim::gpu
