#pragma once
// Flow-field crowds in a zone: each NPC population with `flow` is one crowd::FlowCrowd on the
// scene's map, with one field per destination built once at start (or read from the scene's
// map.fields, baked beforehand by bake_fields) and shared by all its NPCs.
// An NPC's destination is drawn from its id (flowDestination), so it needs no state that
// migration would carry, and every rank agrees on it, ghosts included. An NPC within the
// arrival radius of its goal has arrived: it stands still and leaves the crowd (neither moved
// nor seen), which every rank decides from the position alone. The separation sums run in the
// crowd library's canonical order over owned NPCs and ghosts, so a zone run ends bitwise equal
// on any number of ranks. The scene's doors (map.doors) open and close the crowds' copy of the
// map at their time; the fields they change are rebuilt then, alike on every rank. A crowd
// whose NPCs in the zone have all arrived sleeps, costing nothing per NPC, until an entity
// comes to or leaves the zone (EntityStore::membership).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "ai/grid_map.h"
#include "crowd/vec2.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

class GhostStore;
class ZoneMap;

/// Destination index in [0, count) of the flow NPC with this id (a hash, fixed for its life).
int flowDestination(std::uint64_t id, int count);

/// Steps the flow-field NPC populations of a scene.
class FlowMovement : public ZoneSystem {
 public:
  /// One crowd per population of `scene` with `flow.enabled`, on the zone's `map` (must outlive
  /// this; required when there is such a population), whose doors it follows. Throws SceneError
  /// when a destination lies on a blocked cell.
  FlowMovement(const Scene& scene, const ZoneMap* map);
  ~FlowMovement();

  /// Whether the scene has a flow-field population at all.
  bool active() const override { return !groups_.empty(); }
  /// Widest separation radius of the crowds (the halo must reach this far).
  double reach() const { return reach_; }
  /// Fields rebuilt by the last step because the zone's doors changed the map.
  int fieldsRebuilt() const { return fields_rebuilt_; }
  /// The crowds' map as the doors left it (null without a flow population).
  const ai::GridMap* grid() const;

  /// Rebuilds the fields the zone's doors changed this tick, then advances every flow NPC by one
  /// tick, seeing same-population ghosts. With the scene's `lod`, ctx.players (every player avatar
  /// of the cluster, x-z) and the tick choose each NPC's update (crowd::LevelOfDetail: the
  /// same plan for an NPC on every rank).
  void step(StepContext& ctx) override;
  /// Ghosts carry the crowd population, so that it sees only its own population's NPCs across a
  /// border.
  std::vector<GhostColumn> ghostColumns() const override { return {crowdPopulationColumn()}; }
  /// NPCs still on their way (not arrived) after the last step.
  std::size_t walking() const { return walking_; }
  /// NPC updates (agent steps) done by the last step() (all NPCs on the way without LOD).
  std::size_t updates() const { return updates_; }
  /// NPCs the last step() gathered and looked at, arrived ones included: 0 when every crowd
  /// sleeps (below).
  std::size_t visited() const { return visited_; }
  /// Populations whose crowd slept through the last step(): none of its NPCs in this zone was
  /// on the way, and no entity has come or gone in the zone since it found that, so the step
  /// left it alone (an arrived NPC stands still; a new NPC or one that left wakes it).
  std::size_t sleeping() const { return sleeping_; }

  /// Ids of the NPCs (owned by this zone) that reached their destination in the last step(), in
  /// the order the crowds hold them: each NPC once in its life, as an arrived NPC stands still.
  const std::vector<std::uint64_t>& arrivedLastStep() const { return arrived_now_; }

  /// Whether the NPC at `store` index `i` (a flow NPC) stands at its destination.
  bool arrived(const EntityStore& store, std::size_t i) const;

 private:
  std::size_t advance(EntityStore& store, const GhostStore* ghosts, double dt,
                      std::span<const crowd::Vec2> players, std::int64_t tick);

  struct Group;
  Group* groupOf(std::int32_t population) const;
  /// Rebuilds the fields when the zone's doors changed the map this tick; returns how many.
  int followDoors();

  const ZoneMap* map_;  // the zone's, as its doors leave it
  int fields_rebuilt_ = 0;
  std::vector<std::unique_ptr<Group>> groups_;  // one per flow population
  double reach_ = 0;
  std::size_t walking_ = 0;
  bool lod_ = false;  // the scene's lod key: plan updates by distance to the players
  std::size_t updates_ = 0;
  std::size_t visited_ = 0;
  std::size_t sleeping_ = 0;
  std::vector<std::uint64_t> arrived_now_;
  std::vector<std::uint8_t> arrived_before_;  // per agent of one group, before its step
};

}  // namespace zonesim::zone
