#pragma once
// Where every player avatar of the cluster stands, for the crowds' level of detail: each rank
// owns only its zone's avatars, but an NPC's detail depends on its distance to the nearest
// player anywhere (a player just over a border, or farther than the halo reaches). Players are
// few (one avatar per connected client), so one small allgather per tick gives every rank the
// whole list; the ghosts would not do, as LOD radii (tens of metres) are far wider than a halo.

#include <mpi.h>

#include <vector>

#include "common/scene_lod.h"
#include "crowd/vec2.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// Ground-plane (x, z) positions of every avatar on every rank of `comm`, ordered by rank and
/// then by store order (the order does not matter to a nearest-player distance). Collective:
/// every rank of `comm` must call it.
std::vector<crowd::Vec2> gatherAvatarPositions(MPI_Comm comm, const EntityStore& store);

/// What the crowds' level of detail measures distances to: every avatar of the cluster
/// (gatherAvatarPositions, collective) and then the scene's fixed `lod.observers`.
std::vector<crowd::Vec2> lodPlayers(MPI_Comm comm, const EntityStore& store, const CrowdLod& lod);

}  // namespace zonesim::zone
