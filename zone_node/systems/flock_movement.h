#pragma once
// Flocking NPCs in a zone: each flocking population of the scene is one crowd::Flock. Per tick
// its NPCs are gathered into contiguous ground-plane arrays, the ghosts of the same population
// (other ranks' flockers within the halo) are added as read-only neighbours, the flock steps and
// the new state is written back. The flock's sums are in a canonical order (cells, then ids),
// so the result does not depend on the store's order or on the decomposition. A flock with a
// `goal` steers toward its point through the flock's goal velocity; with the scene's `lod`,
// flockers far from every player step less often (by the time they skipped), the farthest
// following their goal velocity without the neighbour query (crowd::LevelOfDetail).

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "crowd/vec2.h"
#include "gpu/offload.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::crowd {
class Flock;
}  // namespace zonesim::crowd

namespace zonesim::zone {

class GhostStore;

/// Steps the flocking NPC populations of a scene.
class FlockMovement : public ZoneSystem {
 public:
  /// One flock per population of `scene` with `flock.enabled`, each on the backend that
  /// `gpu_mode` ("off", "on", "auto") and the shared thresholds give its share of the
  /// population on `ranks` zones (the batch a zone steps; the same on every rank).
  explicit FlockMovement(const Scene& scene, const std::string& gpu_mode = "off",
                         const gpu::OffloadThresholds& thresholds = {}, int ranks = 1);
  ~FlockMovement();

  /// Whether the scene has a flocking population at all.
  bool active() const override { return !groups_.empty(); }
  /// "opencl" if some population steps on the device, else "cpu"; "none" without flocks.
  const std::string& backendName() const { return backend_; }
  /// Widest neighbour radius of the flocks (the halo must reach this far).
  double reach() const { return reach_; }

  /// Advances every flocking NPC by one tick, seeing same-population ghosts. With the scene's
  /// `lod`, ctx.players (every player avatar of the cluster and the scene's observers, x-z)
  /// and the tick choose each NPC's update (the same plan for an NPC on every rank).
  void step(StepContext& ctx) override;
  /// Ghosts carry the crowd population, so that it sees only its own population's NPCs across a
  /// border.
  std::vector<GhostColumn> ghostColumns() const override { return {crowdPopulationColumn()}; }
  /// NPC updates (agent steps) done by the last step() (every flocker without LOD).
  std::size_t updates() const { return updates_; }

 private:
  /// Returns the number of NPCs stepped.
  std::size_t advance(EntityStore& store, const GhostStore* ghosts, double dt,
                      std::span<const crowd::Vec2> players, std::int64_t tick);

  struct Group;
  const Scene& scene_;
  std::vector<std::unique_ptr<Group>> groups_;  // one per flocking population
  double reach_ = 0;
  std::string backend_ = "none";
  bool lod_ = false;  // the scene's lod key: plan updates by distance to the players
  std::size_t updates_ = 0;
};

}  // namespace zonesim::zone
