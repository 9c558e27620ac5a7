#pragma once
// Which rank solves which rigid-body island, so that contacts across zone borders come out
// exactly as in one world. The engine's Gauss-Seidel solve touches only the two bodies of each
// contact, so islands (bodies linked by possible contacts) are independent: a world holding
// several islands, with its bodies in id order, steps each of them bit for bit as a world
// holding that island alone. Every island is therefore solved whole, by one rank: the owner of
// its lowest id, which gathers the island's bodies from their owners and sends the results
// back (rigid_bodies.h).
//
// Bodies held together by a joint are always one island, and so is everything a cloth may
// touch: the cloths live on one rank, which solves the island of their bodies.
//
// Possible contacts are overlaps of reach boxes: a body's bounds grown by the contact margin
// and twice its travel in the tick (with a tick of gravity), plus a slack. That is a superset
// of the pairs the engine's broadphase can find, so an island here may join several of the
// engine's islands, which changes nothing. Each zone joins its own bodies; bodies whose reach
// box, grown by the largest reach box in the cluster, crosses the zone's rectangle are shared
// with every rank (label and box), and each rank joins those across zones the same way.

#include <cstdint>
#include <span>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/entity_id.h"
#include "physics/aabb.h"

namespace zonesim::zone {

/// A pair of bodies that must be in one island (a joint), by index or by id.
using IndexLink = std::pair<std::uint32_t, std::uint32_t>;
using BodyLink = std::pair<EntityId, EntityId>;

/// Each body's island label among `boxes` (overlapping boxes join, and linked bodies): the
/// lowest id in it. ids must be sorted ascending, one per box.
std::vector<EntityId> joinOverlapping(std::span<const EntityId> ids,
                                      std::span<const physics::Aabb> boxes,
                                      std::span<const IndexLink> links = {});

/// A body near the zone's border, as every rank sees it.
struct BorderBody {
  EntityId label;  ///< its island within its own zone (the lowest id there)
  EntityId body;   ///< the body itself (none for a cloth)
  int rank = 0;    ///< its owner
  physics::Aabb box;
};

/// Where an island of a zone is solved.
struct IslandSolver {
  EntityId island;  ///< the lowest id of the whole island, across zones
  int rank = 0;     ///< the rank that owns that body
};

/// The zone islands that touch across borders or are linked, joined: for every label in
/// `shared`, the whole island's lowest id and the rank holding it. Every rank computes the same
/// from the same list. Both bodies of a link must be in `shared` for it to count.
std::unordered_map<std::uint64_t, IslandSolver> joinAcrossZones(
    std::span<const BorderBody> shared, std::span<const BodyLink> links = {});

/// BorderBody list <-> the words the cluster gathers (label, body, rank, box bits).
inline constexpr std::size_t kBorderBodyWords = 9;
void appendWords(const BorderBody& b, std::vector<std::uint64_t>& out);
/// Throws std::runtime_error when the list is not whole records.
std::vector<BorderBody> borderBodiesOf(std::span<const std::uint64_t> words);

}  // namespace zonesim::zone
