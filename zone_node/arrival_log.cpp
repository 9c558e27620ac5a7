#include "zone_node/arrival_log.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace zonesim::zone {

static_assert(sizeof(FlowArrival) == 2 * sizeof(std::uint64_t),
              "gathered as pairs of MPI_UINT64_T: no padding");

void ArrivalLog::record(std::uint64_t tick, std::span<const std::uint64_t> ids) {
  if (!enabled_) return;
  for (std::uint64_t id : ids) arrivals_.push_back({id, tick});
}

void ArrivalLog::write(MPI_Comm comm, const std::string& path) const {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  int n = int(arrivals_.size() * 2);
  std::vector<int> counts(static_cast<std::size_t>(size)), displs(static_cast<std::size_t>(size));
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<FlowArrival> all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      displs[std::size_t(r)] = total;
      total += counts[std::size_t(r)];
    }
    all.resize(std::size_t(total) / 2);
  }
  MPI_Gatherv(arrivals_.data(), n, MPI_UINT64_T, all.data(), counts.data(), displs.data(),
              MPI_UINT64_T, 0, comm);
  if (rank != 0) return;
  std::sort(all.begin(), all.end(), [](const FlowArrival& a, const FlowArrival& b) {
    return a.id != b.id ? a.id < b.id : a.tick < b.tick;
  });
  auto twice = std::adjacent_find(all.begin(), all.end(),
                                  [](const auto& a, const auto& b) { return a.id == b.id; });
  if (twice != all.end())
    throw std::runtime_error("--arrivals: NPC " + std::to_string(twice->id) +
                             " arrived twice (ticks " + std::to_string(twice->tick) + " and " +
                             std::to_string(std::next(twice)->tick) + ")");
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  std::fputs("id,tick\n", f);
  for (const FlowArrival& a : all)
    std::fprintf(f, "%llu,%llu\n", (unsigned long long)a.id, (unsigned long long)a.tick);
  if (std::fclose(f) != 0)
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
}

}  // namespace zonesim::zone
