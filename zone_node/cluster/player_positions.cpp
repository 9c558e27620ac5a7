#include "zone_node/cluster/player_positions.h"

namespace zonesim::zone {

std::vector<crowd::Vec2> gatherAvatarPositions(MPI_Comm comm, const EntityStore& store) {
  std::vector<double> mine;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Avatar) continue;
    mine.push_back(store.pos[i].x());
    mine.push_back(store.pos[i].z());
  }
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
  std::vector<double> all(static_cast<std::size_t>(total));
  MPI_Allgatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), offsets.data(),
                 MPI_DOUBLE, comm);
  std::vector<crowd::Vec2> players;
  players.reserve(all.size() / 2);
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) players.push_back({all[k], all[k + 1]});
  return players;
}

std::vector<crowd::Vec2> lodPlayers(MPI_Comm comm, const EntityStore& store, const CrowdLod& lod) {
  std::vector<crowd::Vec2> players = gatherAvatarPositions(comm, store);
  for (auto [x, z] : lod.observers) players.push_back({x, z});
  return players;
}

}  // namespace zonesim::zone
