#pragma once
// Per-kernel offload decisions for --gpu auto: each workload has its own item count from which
// the device pays, taken from measured defaults or from a timed probe at start-up. The decision
// logic is pure (testable without timing); the probe lives in gpu/offload_probe.h.

#include <cstddef>
#include <limits>
#include <span>
#include <string_view>

#include "gpu/backend.h"

namespace zonesim::gpu {

/// The kernels with their own threshold: the particle system, and zone flocks (gpu::PlanarFlock
/// against the crowd library's CPU flock, probed by zone_node/systems/flock_backend.h).
enum class Workload { Particles, Flock };

/// "particles" or "flock".
const char* workloadName(Workload workload);

/// Never offload under auto (the device lost at every probed size).
inline constexpr std::size_t kNeverOffload = std::numeric_limits<std::size_t>::max();

/// Item counts from which auto offloads, one per workload.
struct OffloadThresholds {
  std::size_t particles = kAutoGpuThreshold;  ///< Live particles.
  std::size_t flock = kNeverOffload;          ///< Agents in one zone flock.
  /// The threshold of workload.
  std::size_t of(Workload workload) const;
};

/// The thresholds before a probe, or when it fails on a device that exists: particles from
/// kAutoGpuThreshold (measured on a quiet machine, gpu/backend.h); flocks never, since on PoCL
/// sharing two loaded cores with the CPU path they did not win reliably (docs/benchmarks.md);
/// zone_node probes them under auto (zone_node/systems/offload_probe.h).
OffloadThresholds defaultThresholds();

/// One timed probe: seconds per step on each path at n items.
struct ProbeSample {
  std::size_t n = 0;    ///< Items.
  double cpu_s = 0;     ///< CPU path, seconds per step.
  double device_s = 0;  ///< OpenCL path, seconds per step (launch, sync, needed copies).
};

/// The count from which the device wins at every larger probed size: where log(cpu / device)
/// crosses zero, interpolated linearly in log n between the last losing and the first winning
/// probe; the smallest n if the device wins everywhere; kNeverOffload if it loses at the
/// largest. Samples may come in any order; empty gives kNeverOffload.
std::size_t crossover(std::span<const ProbeSample> samples);

/// Off gives Cpu; On gives OpenCl; Auto gives OpenCl only when a device exists and n reaches
/// the workload's threshold.
Backend chooseBackend(GpuMode mode, Workload workload, std::size_t n, bool opencl_available,
                      const OffloadThresholds& thresholds);

}  // namespace zonesim::gpu
