#pragma once
// The start-up probe behind --gpu auto for the particle system: times it on both paths at a few
// sizes; gpu/offload.h's crossover turns the samples into a threshold.
// Zone flocks have their CPU path in the crowd library, so zone_node probes them itself
// (zone_node/systems/flock_backend.h) with the same sizes and crossover.

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "gpu/offload.h"

namespace zonesim::gpu {

class ClRuntime;

/// Sizes the start-up probe times: 1,000 to 64,000 items, about a second in all on PoCL.
inline constexpr std::size_t kProbeSizes[] = {1'000, 4'000, 16'000, 64'000};

/// Times the particle system on the CPU and on runtime's device at each size (best of a few
/// ticks each).
std::vector<ProbeSample> probeParticles(std::shared_ptr<ClRuntime> runtime,
                                        std::span<const std::size_t> sizes);

}  // namespace zonesim::gpu
