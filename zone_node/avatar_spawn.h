#pragma once
// What a new avatar is made of: the entity a zone creates for a player's spawn request, with
// the top speed and, for a flyer, the height of the player's kind (common/player_kind.h).

#include <cstdint>
#include <optional>

#include "zone_node/entity_store.h"

namespace zonesim {
struct Scene;
}

namespace zonesim::zone {

/// The avatar of player_id at (x, z), clamped into the world, on the ground or at its kind's
/// height, without an id yet (the creator gives it one); nothing when the scene lists no kind
/// of that id (the gateway checked the Hello, but a gateway started with another scene could
/// still ask).
std::optional<EntityRecordData> newAvatar(const Scene& scene, std::uint64_t player_id, double x,
                                          double z, std::uint8_t kind);

}  // namespace zonesim::zone
