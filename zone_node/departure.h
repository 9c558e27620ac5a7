#pragma once
// An entity that left this rank in a tick: migrated to another zone or destroyed. Migration
// produces them and the publisher tells the gateways; a header of its own keeps <mpi.h> away
// from the publisher.

#include <cstdint>

#include "common/entity_id.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// An entity that left this rank during the exchange, or was destroyed here.
struct Departure {
  EntityId id;
  EntityKind kind;
  int to_rank;              ///< -1: destroyed rather than migrated
  int last_cell;            ///< interest cell it was last published in here (-1: never)
  std::uint64_t player_id;  ///< for avatars
  bool announced_avatar;    ///< an avatar the gateways know: its move is a handoff
};

}  // namespace zonesim::zone
