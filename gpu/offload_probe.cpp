#include "gpu/offload_probe.h"

#include <mutex>
#include <optional>

#include "gpu/default_runtime.h"
#include "gpu/gpu_error.h"
#include "gpu/workload_scene.h"

namespace zonesim::gpu {
namespace {

// Enough ticks to average out a scheduler slice, few enough to keep start-up short.
constexpr int kProbeSteps = 3;
constexpr int kProbeRepeats = 2;

}  // namespace

std::vector<ProbeSample> probeWorkload(Workload workload, std::shared_ptr<ClRuntime> runtime,
                                       std::span<const std::size_t> sizes) {
  std::vector<ProbeSample> samples;
  for (std::size_t n : sizes) {
    WorkloadScene cpu(workload, Backend::Cpu, n);
    WorkloadScene device(workload, Backend::OpenCl, n, runtime);
    samples.push_back({n, secondsPerTick(cpu, kProbeSteps, kProbeRepeats),
                       secondsPerTick(device, kProbeSteps, kProbeRepeats)});
  }
  return samples;
}

OffloadThresholds calibrateThresholds(std::shared_ptr<ClRuntime> runtime,
                                      std::span<const std::size_t> sizes) {
  OffloadThresholds t;
  t.particles = crossover(probeWorkload(Workload::Particles, runtime, sizes));
  t.boids = crossover(probeWorkload(Workload::Boids, runtime, sizes));
  t.crowd = crossover(probeWorkload(Workload::Crowd, runtime, sizes));
  return t;
}

std::size_t autoThreshold(Workload workload) {
  static std::mutex mutex;
  static std::optional<std::size_t> cached[3];
  std::lock_guard<std::mutex> lock(mutex);
  std::optional<std::size_t>& slot = cached[static_cast<int>(workload)];
  if (!slot) {
    slot = defaultThresholds().of(workload);
    // A device that fails during the probe is treated like a missing one: auto must not stop.
    if (openClAvailable()) {
      try {
        slot = crossover(probeWorkload(workload, defaultRuntime(), kProbeSizes));
      } catch (const GpuError&) {
      }
    }
  }
  return *slot;
}

Backend selectBackend(std::string_view mode, Workload workload, std::size_t n) {
  GpuMode parsed = parseGpuMode(mode);
  if (parsed != GpuMode::Auto) return chooseBackend(parsed, workload, n, false, {});
  // crossover() never returns less than the smallest probe size, so no probe is needed here.
  if (n < kProbeSizes[0]) return Backend::Cpu;
  bool available = openClAvailable();
  OffloadThresholds t;
  t.particles = t.boids = t.crowd = available ? autoThreshold(workload) : kNeverOffload;
  return chooseBackend(parsed, workload, n, available, t);
}

}  // namespace zonesim::gpu
