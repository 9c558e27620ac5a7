#pragma once
// The start-up probe behind --gpu auto: times each workload on both paths at a few sizes and
// turns the samples into thresholds (gpu/offload.h's crossover), once per process.

#include <cstddef>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "gpu/offload.h"

namespace zonesim::gpu {

class ClRuntime;

/// Sizes the start-up probe times: 1,000 to 64,000 items, about a second in all on PoCL.
inline constexpr std::size_t kProbeSizes[] = {1'000, 4'000, 16'000, 64'000};

/// Times workload on the CPU and on runtime's device at each size (best of a few ticks each).
std::vector<ProbeSample> probeWorkload(Workload workload, std::shared_ptr<ClRuntime> runtime,
                                       std::span<const std::size_t> sizes);

/// Probes every workload on runtime and returns the crossovers.
OffloadThresholds calibrateThresholds(std::shared_ptr<ClRuntime> runtime,
                                      std::span<const std::size_t> sizes = kProbeSizes);

/// The threshold --gpu auto uses for workload: probed on the default device at the first call
/// for that workload and kept for the process (so a zone without flocks never probes them);
/// defaultThresholds()'s when there is no device or the probe fails.
std::size_t autoThreshold(Workload workload);

/// The --gpu decision for n items of workload in a single process: parseGpuMode(mode), then
/// chooseBackend with autoThreshold(workload). On and off never probe, nor does auto below the
/// smallest probe size (the crossover is never below it). Probes are timed per process, so
/// ranks that must agree should probe on one rank (calibrateThresholds), broadcast the
/// OffloadThresholds and call chooseBackend with them.
Backend selectBackend(std::string_view mode, Workload workload, std::size_t n);

}  // namespace zonesim::gpu
