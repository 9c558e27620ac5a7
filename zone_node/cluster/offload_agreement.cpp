#include "zone_node/cluster/offload_agreement.h"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <thread>

#include "common/log.h"
#include "gpu/gpu_error.h"

namespace zonesim::zone {

void shareCpuDeviceAmongLocalRanks(MPI_Comm comm) {
  MPI_Comm local = MPI_COMM_NULL;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &local);
  int ranks_here = 1;
  MPI_Comm_size(local, &ranks_here);
  MPI_Comm_free(&local);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const unsigned share = std::max(1u, cores / unsigned(std::max(1, ranks_here)));
  // Only PoCL reads this; a setting from the environment wins (overwrite = 0).
  setenv("POCL_MAX_PTHREAD_COUNT", std::to_string(share).c_str(), 0);
}

gpu::OffloadThresholds agreedThresholds(MPI_Comm comm, bool probe, const ThresholdProbe& measure) {
  shareCpuDeviceAmongLocalRanks(comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  gpu::OffloadThresholds t = gpu::defaultThresholds();
  if (rank == 0 && probe && gpu::openClAvailable()) {
    try {
      measure(t);
    } catch (const gpu::GpuError& e) {
      ZS_WARN("offload probe failed (%s); using the default thresholds", e.what());
    }
  }
  std::uint64_t wire[2] = {t.particles, t.flock};
  MPI_Bcast(wire, 2, MPI_UINT64_T, 0, comm);
  return {std::size_t(wire[0]), std::size_t(wire[1])};
}

}  // namespace zonesim::zone
