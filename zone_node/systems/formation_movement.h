#pragma once
// Formations in a zone: each NPC population with `formation` is one fixed group on the scene's
// map (crowd::Formation's parts). The centre's route is planned with A* when the zone starts,
// and the centre is stepped identically on every rank, so its position at a tick is a function
// of the scene and the tick alone: no rank tells another where it is. A member's slot follows
// from its id (its index in the population), its mode and rejoin path ride in the entity
// (NpcData::crowd_*) and migrate with it, and it pushes apart from the other members, ghosts
// included, summed in ascending id order. So a zone run ends bitwise equal on any number of
// ranks.

#include <cstdint>
#include <memory>
#include <vector>

#include "common/scene_npcs.h"
#include "crowd/vec2.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::crowd {
class FormationCentre;
}

namespace zonesim::zone {

class GhostStore;
struct WorldMap;

/// Steps the formation NPC populations of a scene.
class FormationMovement : public ZoneSystem {
 public:
  /// One group per population of `scene` with `formation.enabled`, on `map` (must outlive
  /// this; required when there is such a population). Throws SceneError when a route point
  /// lies on a blocked cell or cannot be reached from the one before.
  FormationMovement(const Scene& scene, const WorldMap* map);
  ~FormationMovement();

  /// Whether the scene has a formation at all.
  bool active() const override { return !groups_.empty(); }
  /// Widest separation radius of the formations (the halo must reach this far).
  double reach() const { return reach_; }

  /// Advances every formation to the end of tick `tick` (the centres take every step from tick
  /// 0 on, so a zone restarted at a later tick catches up) and steps the members of `store`,
  /// seeing same-population ghosts.
  void step(StepContext& ctx) override;
  /// Ghosts carry the crowd population, so that it sees only its own population's NPCs across a
  /// border.
  std::vector<GhostColumn> ghostColumns() const override { return {crowdPopulationColumn()}; }

  /// Number of formations (in population order).
  std::size_t count() const { return groups_.size(); }
  /// Centre of formation `g` after the last step.
  const crowd::FormationCentre& centre(std::size_t g) const;
  /// Population index of formation `g`.
  std::int32_t population(std::size_t g) const;
  /// World position (plane) of the slot of the NPC at `store` index `i` (a formation member).
  crowd::Vec2 slotPosition(const EntityStore& store, std::size_t i) const;
  /// Rejoin paths planned on this rank so far.
  int rejoinPlans() const;
  /// Member steps done by the last step() (every member without LOD).
  std::size_t updates() const { return updates_; }

 private:
  struct Group;
  Group* groupOf(std::int32_t population) const;
  const Scene& scene_;
  std::vector<std::unique_ptr<Group>> groups_;
  double reach_ = 0;
  std::size_t updates_ = 0;
};

}  // namespace zonesim::zone
