#include "zone_node/cluster/player_positions.h"

#include "zone_node/cluster/value_gather.h"

namespace zonesim::zone {

std::vector<crowd::Vec2> gatherAvatarPositions(MPI_Comm comm, const EntityStore& store) {
  std::vector<double> mine;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Avatar) continue;
    mine.push_back(store.pos[i].x());
    mine.push_back(store.pos[i].z());
  }
  std::vector<double> all = gatherValues(comm, mine);
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
