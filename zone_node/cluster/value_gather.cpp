#include "zone_node/cluster/value_gather.h"

namespace zonesim::zone {

namespace {

template <class T>
std::vector<T> gather(MPI_Comm comm, const std::vector<T>& mine, MPI_Datatype type) {
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
  std::vector<T> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(mine.data(), count, type, all.data(), counts.data(), offsets.data(), type, comm);
  return all;
}

template <class T>
std::vector<T> gatherToRoot(MPI_Comm comm, std::span<const T> mine, MPI_Datatype type) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int count = int(mine.size());
  std::vector<int> counts(static_cast<std::size_t>(size)), offsets(static_cast<std::size_t>(size));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  int total = 0;
  for (int r = 0; r < size; ++r) {
    offsets[std::size_t(r)] = total;
    total += counts[std::size_t(r)];
  }
  std::vector<T> all(rank == 0 ? static_cast<std::size_t>(total) : 0);
  MPI_Gatherv(mine.data(), count, type, all.data(), counts.data(), offsets.data(), type, 0, comm);
  return all;
}

}  // namespace

std::vector<std::uint64_t> gatherValues(MPI_Comm comm, const std::vector<std::uint64_t>& mine) {
  return gather(comm, mine, MPI_UINT64_T);
}

std::vector<double> gatherValues(MPI_Comm comm, const std::vector<double>& mine) {
  return gather(comm, mine, MPI_DOUBLE);
}

std::vector<std::uint64_t> gatherValuesToRoot(MPI_Comm comm, std::span<const std::uint64_t> mine) {
  return gatherToRoot(comm, mine, MPI_UINT64_T);
}

std::vector<double> gatherValuesToRoot(MPI_Comm comm, std::span<const double> mine) {
  return gatherToRoot(comm, mine, MPI_DOUBLE);
}

}  // namespace zonesim::zone
