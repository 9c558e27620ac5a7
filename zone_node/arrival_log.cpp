#include "zone_node/arrival_log.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "zone_node/cluster/value_gather.h"

namespace zonesim::zone {

void ArrivalLog::record(std::uint64_t tick, std::span<const std::uint64_t> ids) {
  if (!enabled_) return;
  for (std::uint64_t id : ids) arrivals_.push_back({id, tick});
}

void ArrivalLog::write(MPI_Comm comm, const std::string& path) const {
  std::vector<std::uint64_t> mine;  // sent as a flat list of id, tick pairs
  mine.reserve(arrivals_.size() * 2);
  for (const FlowArrival& a : arrivals_) mine.insert(mine.end(), {a.id, a.tick});
  const std::vector<std::uint64_t> flat = gatherValuesToRoot(comm, mine);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0) return;
  std::vector<FlowArrival> all(flat.size() / 2);
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = {flat[2 * i], flat[2 * i + 1]};
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
