#include "zone_node/cluster/trail_exchange.h"

#include <climits>
#include <stdexcept>

namespace zonesim::zone {

void sumTrailDeltas(MPI_Comm comm, std::span<std::int64_t> deltas) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size == 1 || deltas.empty()) return;
  if (deltas.size() > std::size_t(INT_MAX)) throw std::length_error("sumTrailDeltas: too long");
  MPI_Allreduce(MPI_IN_PLACE, deltas.data(), int(deltas.size()), MPI_INT64_T, MPI_SUM, comm);
}

}  // namespace zonesim::zone
