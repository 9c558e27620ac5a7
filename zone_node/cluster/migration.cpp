#include "zone_node/cluster/migration.h"

namespace zonesim::zone {

Migrator::Migrator(MPI_Comm comm, int rank, int size)
    : rank_(rank), size_(size), bytes_(comm, size) {}

MigrationResult Migrator::exchange(EntityStore& store, const ZoneLayout& layout, std::uint64_t tick,
                                   std::vector<std::vector<ForwardedInput>>& forward) {
  MigrationResult result;
  std::vector<MigrationPayload> outgoing(size_);
  std::vector<std::size_t> leavers;
  // A lone zone owns the whole world: nothing can leave it, so its entities are not scanned.
  const std::size_t scanned = size_ > 1 ? store.size() : 0;
  for (std::size_t i = 0; i < scanned; ++i) {
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

  bytes_.begin();
  for (int r = 0; r < size_; ++r) {
    if (r < int(forward.size())) outgoing[r].inputs.swap(forward[r]);
    if (outgoing[r].entities.empty() && outgoing[r].inputs.empty()) continue;
    outgoing[r].tick = tick;
    outgoing[r].from_rank = rank_;
    bytes_.outgoing(r) = encodeMigration(outgoing[r]);
  }
  for (auto& f : forward) f.clear();
  bytes_.exchange();
  result.bytes_sent = bytes_.bytesSent();

  for (int r = 0; r < size_; ++r) {
    std::span<const std::uint8_t> bytes = bytes_.received(r);
    if (bytes.empty()) continue;
    MigrationPayload in = decodeMigration(bytes);
    for (const EntityRecordData& e : in.entities) result.arrived.push_back({store.add(e), r, e.id});
    result.inputs.insert(result.inputs.end(), in.inputs.begin(), in.inputs.end());
  }
  return result;
}

}  // namespace zonesim::zone
