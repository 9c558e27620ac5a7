#pragma once
// What --gpu probe times in a zone: the kernels zone_node runs on a device, for the thresholds
// rank 0 measures and every rank then shares (zone_node/cluster/offload_agreement.h).

#include "gpu/offload.h"

namespace zonesim::zone {

/// Sets the particle threshold and the boids threshold from timings of particles and of the
/// zone flocks on the CPU and the device, and logs them. Throws gpu::GpuError when a device
/// fails (the particle threshold may be set by then).
void probeZoneThresholds(gpu::OffloadThresholds& t);

}  // namespace zonesim::zone
