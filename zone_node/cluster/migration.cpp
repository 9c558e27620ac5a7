#include "zone_node/cluster/migration.h"

#include <stdexcept>
#include <string>

namespace zonesim::zone {

namespace {
void mpiCheck(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string(what) + " failed");
}
}  // namespace

Migrator::Migrator(MPI_Comm comm, int rank, int size)
    : comm_(comm),
      rank_(rank),
      size_(size),
      send_counts_(size),
      recv_counts_(size),
      send_displs_(size),
      recv_displs_(size) {}

MigrationResult Migrator::exchange(EntityStore& store, const ZoneLayout& layout, std::uint64_t tick,
                                   std::vector<std::vector<ForwardedInput>>& forward) {
  MigrationResult result;
  std::vector<MigrationPayload> outgoing(size_);
  std::vector<std::size_t> leavers;
  for (std::size_t i = 0; i < store.size(); ++i) {
    int owner = layout.ownerOf(store.pos[i].x(), store.pos[i].z());
    if (owner == rank_) continue;
    outgoing[owner].entities.push_back(store.record(i));
    leavers.push_back(i);
    result.departed.push_back({store.id[i], store.kind[i], owner, store.dr[i].cell,
                               store.avatar[i].player_id,
                               store.kind[i] == EntityKind::Avatar && store.avatar[i].announced});
  }
  // Descending order: the entity swapped into a hole has a higher index and was already kept.
  for (auto it = leavers.rbegin(); it != leavers.rend(); ++it) store.removeAt(*it);

  send_buf_.clear();
  for (int r = 0; r < size_; ++r) {
    send_displs_[r] = int(send_buf_.size());
    send_counts_[r] = 0;
    if (r < int(forward.size())) outgoing[r].inputs.swap(forward[r]);
    if (outgoing[r].entities.empty() && outgoing[r].inputs.empty()) continue;
    outgoing[r].tick = tick;
    outgoing[r].from_rank = rank_;
    std::vector<std::uint8_t> bytes = encodeMigration(outgoing[r]);
    send_buf_.insert(send_buf_.end(), bytes.begin(), bytes.end());
    send_counts_[r] = int(bytes.size());
  }
  for (auto& f : forward) f.clear();
  result.bytes_sent = send_buf_.size();

  mpiCheck(MPI_Alltoall(send_counts_.data(), 1, MPI_INT, recv_counts_.data(), 1, MPI_INT, comm_),
           "MPI_Alltoall");
  int total = 0;
  for (int r = 0; r < size_; ++r) {
    recv_displs_[r] = total;
    total += recv_counts_[r];
  }
  recv_buf_.resize(std::size_t(total));
  mpiCheck(
      MPI_Alltoallv(send_buf_.data(), send_counts_.data(), send_displs_.data(), MPI_BYTE,
                    recv_buf_.data(), recv_counts_.data(), recv_displs_.data(), MPI_BYTE, comm_),
      "MPI_Alltoallv");

  for (int r = 0; r < size_; ++r) {
    if (recv_counts_[r] == 0) continue;
    MigrationPayload in = decodeMigration(std::span<const std::uint8_t>(
        recv_buf_.data() + recv_displs_[r], std::size_t(recv_counts_[r])));
    for (const EntityRecordData& e : in.entities) result.arrived.push_back({store.add(e), r});
    result.inputs.insert(result.inputs.end(), in.inputs.begin(), in.inputs.end());
  }
  return result;
}

}  // namespace zonesim::zone
