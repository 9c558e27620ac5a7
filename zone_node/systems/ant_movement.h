#pragma once
// Ant colonies in a zone: each NPC population with `colony` is a colony on the scene's map. Its
// ants are entities walking from cell centre to cell centre. The colony rule is crowd/'s: an
// ant's trip (search, dead ends, the shortened way home, laying deposit / (route length) on
// every cell) is crowd/ant_trip_rule.h's, riding in the entity as AntData (crowd::AntTrip);
// the step choice is chooseAntStep (crowd/ant_step.h, the one AntColony uses too); the trail is
// a fixed-point grid per colony that evaporates every tick (crowd/ant_trail.h). This system is
// the adapter: it maps the scene's colonies and entities to those, moves the ants between cell
// centres, and sums the trail deposits over the ranks.
//
// Decomposition: the trail grid is global state that ants on every rank read and lay. Trails
// are fixed-point integers: each rank adds up its own ants' deposits of a tick (deltas()), the
// zone sums the deltas of all ranks (one MPI_Allreduce, exact and order-free in integers:
// cluster/trail_exchange.h), and applyTrails() evaporates and adds them with integer
// arithmetic, alike on every rank. An ant's choice reads the trails as they stood at the start
// of the tick and a random number keyed by (seed, ant id, tick), and its trip rides in the
// entity (NpcData::crowd), so a run ends bitwise equal on any number of ranks.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "ai/octile.h"
#include "crowd/ant_trail.h"
#include "crowd/ant_trip.h"
#include "crowd/lod.h"
#include "zone_node/entity_store.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

struct WorldMap;

// The colony rule's names where the zone's code and tests read them.
using crowd::AntMode;
using crowd::kTrailScale;

/// Per-colony figures of this rank's ants.
struct ColonyStats {
  std::uint64_t trips = 0;  ///< ants back at the nest with food, since the start
  double length_sum = 0;    ///< summed route length (m) of those trips
  double last_length = 0;   ///< route length of the latest of them
};

/// Steps the ant colony NPC populations of a scene.
class AntMovement : public ZoneSystem {
 public:
  /// One colony per population of `scene` with `colony.enabled`, on `map` (must outlive this;
  /// required when there is such a population). Throws SceneError when the nest or the food
  /// lies on a blocked cell.
  AntMovement(const Scene& scene, const WorldMap* map);
  ~AntMovement();

  /// Whether the scene has a colony at all.
  bool active() const override { return !colonies_.empty(); }

  /// One tick: walk(), the deposits summed over every rank (ctx.cluster.sum, collective), then
  /// applyTrails(), so every rank's trails stay the same.
  void step(StepContext& ctx) override;
  /// Moves every ant of `store` by one tick (`tick` from 0: time tick * dt) reading the trails
  /// as they stand, and adds the ants' deposits to deltas() (cleared first). Under the scene's
  /// `lod`, an ant far from every one of `players` walks only on its tick of every period, as
  /// far as the period's ticks would have taken it, deciding at most once per tick it stands
  /// for.
  void walk(EntityStore& store, std::uint64_t tick, double dt,
            std::span<const crowd::Vec2> players = {});
  /// Ant walks done by the last walk() (every ant without LOD).
  std::size_t updates() const { return updates_; }
  /// This tick's deposits of the ants on this rank, every colony's cells one after another;
  /// to be summed over all ranks before applyTrails().
  std::span<std::int64_t> deltas() { return deltas_; }
  /// Evaporates every trail by one tick and adds deltas() (summed over the ranks).
  void applyTrails();

  /// Number of colonies (in population order).
  std::size_t count() const { return colonies_.size(); }
  /// Population index of colony `c`.
  std::int32_t population(std::size_t c) const;
  /// Trail of colony `c` on cell (x, y), in pheromone units.
  double trail(std::size_t c, ai::Cell cell) const;
  /// Sum of colony `c`'s trail over the map, in pheromone units.
  double totalTrail(std::size_t c) const;
  /// Colony `c`'s preferred route: from the nest always the strongest unvisited neighbour;
  /// empty when it dead-ends before the food.
  std::vector<ai::Cell> trailRoute(std::size_t c) const;
  /// Figures of colony `c`'s ants on this rank.
  const ColonyStats& stats(std::size_t c) const;

 private:
  struct Colony;
  std::vector<std::unique_ptr<Colony>> colonies_;
  std::vector<std::int64_t> deltas_;
  std::uint64_t seed_ = 0;
  bool lod_ = false;  // the scene's lod key
  crowd::LodSettings lod_settings_;
  std::size_t updates_ = 0;
};

}  // namespace zonesim::zone
