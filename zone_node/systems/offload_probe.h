#pragma once
// What a zone times at start-up for --gpu auto and probe: the kernels zone_node runs on a
// device, for the thresholds rank 0 measures and every rank then shares
// (zone_node/cluster/offload_agreement.h).

#include <string_view>

#include "gpu/offload.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// The workloads a zone probes.
struct ProbedWorkloads {
  bool particles = false;
  bool flocks = false;
  bool any() const { return particles || flocks; }
};

/// --gpu probe: both workloads, when the scene has particles or flocks. auto: the flocks, when
/// some flocking population holds at least the smallest probed size (gpu::kProbeSizes; a
/// smaller one never reaches a probed crossover, so timing would be wasted); the particles keep
/// their measured default. on and off: nothing.
ProbedWorkloads probedWorkloads(const Scene& scene, std::string_view gpu_mode);

/// Sets the thresholds of the workloads in `what` from timings on the CPU and the device (the
/// particle system; the zone flock, the crowd flock against gpu::PlanarFlock), keeps the other,
/// and logs them. Throws gpu::GpuError when a device fails (a threshold may be set by then).
void probeZoneThresholds(gpu::OffloadThresholds& t, ProbedWorkloads what);

}  // namespace zonesim::zone
