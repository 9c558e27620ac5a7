#include "zone_node/cluster/value_gather.h"

namespace zonesim::zone {

std::vector<std::uint64_t> gatherValues(MPI_Comm comm, const std::vector<std::uint64_t>& mine) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  int count = int(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size));
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  int total = 0;
  for (int r = 0; r < size; ++r) {
    offsets[std::size_t(r)] = total;
    total += counts[std::size_t(r)];
  }
  std::vector<std::uint64_t> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(mine.data(), count, MPI_UINT64_T, all.data(), counts.data(), offsets.data(),
                 MPI_UINT64_T, comm);
  return all;
}

}  // namespace zonesim::zone
