#pragma once
// One --gpu auto decision for the whole cluster. The start-up probe (gpu/offload_probe.h) times
// kernels on the CPU and the device; timings differ from rank to rank, and ranks that chose
// differently would integrate the same particles in float on one and double on another. So
// rank 0 alone probes and broadcasts its thresholds; every rank then decides from the same
// numbers.

#include <mpi.h>

#include <functional>

#include "gpu/offload.h"

namespace zonesim::zone {

/// Caps a PoCL CPU device at this rank's share of the machine's cores (cores / ranks on this
/// machine) unless POCL_MAX_PTHREAD_COUNT is set: PoCL otherwise starts a worker per core in
/// every rank, and two ranks on two cores then ran ticks of hundreds of milliseconds instead
/// of a few (docs/gpu.md). Collective; must run before the process opens OpenCL.
void shareCpuDeviceAmongLocalRanks(MPI_Comm comm);

/// Refines default thresholds by timing kernels on this rank; may throw gpu::GpuError, which
/// keeps what it had set by then.
using ThresholdProbe = std::function<void(gpu::OffloadThresholds&)>;

/// The thresholds every rank uses: gpu::defaultThresholds(), refined by `measure` on rank 0
/// when `probe` (and a device exists there); collective. Calls shareCpuDeviceAmongLocalRanks
/// first.
gpu::OffloadThresholds agreedThresholds(MPI_Comm comm, bool probe, const ThresholdProbe& measure);

}  // namespace zonesim::zone
