#pragma once
// One --gpu auto decision for the whole cluster. The start-up probe (gpu/offload_probe.h) times
// kernels on the CPU and the device; timings differ from rank to rank, and ranks that chose
// differently would integrate the same particles in float on one and double on another. So
// rank 0 alone probes and broadcasts its thresholds; every rank then decides from the same
// numbers.

#include <mpi.h>

#include "gpu/offload.h"

namespace zonesim::zone {

/// Caps a PoCL CPU device at this rank's share of the machine's cores (cores / ranks on this
/// machine) unless POCL_MAX_PTHREAD_COUNT is set: PoCL otherwise starts a worker per core in
/// every rank, and two ranks on two cores then ran ticks of hundreds of milliseconds instead
/// of a few (docs/gpu.md). Collective; must run before the process opens OpenCL.
void shareCpuDeviceAmongLocalRanks(MPI_Comm comm);

/// The thresholds every rank uses: probed on rank 0 when `probe` (and a device exists there),
/// else gpu::defaultThresholds(); collective. The boids threshold is the zone flocks' own
/// (probeFlockBackends), not gpu::Flock's. Calls shareCpuDeviceAmongLocalRanks first.
gpu::OffloadThresholds agreedThresholds(MPI_Comm comm, bool probe);

}  // namespace zonesim::zone
