#pragma once
// The zone's rigid bodies on the physics engine (zone_node/physics): spheres, boxes and capsules
// on a static ground and inside the world's walls. The engine's world persists across ticks
// (warm starting, islands, sleeping) and is rebuilt from the entity store only when the zone's
// set of bodies changes (a body migrated in or out), which costs that tick its warm start.
// A zone whose bodies all sleep skips the step entirely.
//
// Contacts across a zone border (LAMMPS' reverse_comm, "newton on"): of two neighbouring zones
// the lower rank resolves every contact between their bodies. It adds the higher ranks'
// rigid-body ghosts to its world as foreign bodies (pushed by its own bodies, touching nothing
// else), solves, and hands each ghost's velocity change back to the owner, which adds it to its
// body. The solver applies equal and opposite impulses, so momentum is conserved to round-off;
// the owner's body feels the push one tick late in position (its velocity is right).

#include <cstdint>
#include <memory>
#include <vector>

#include "common/entity_id.h"
#include "common/math.h"
#include "common/scene.h"
#include "zone_node/cluster/ghost_store.h"
#include "zone_node/entity_store.h"

namespace zonesim::physics {
class World;
}

namespace zonesim::zone {

class RigidBodySystem {
 public:
  /// `rank`: this zone's rank, which decides whose contacts across a border it resolves.
  RigidBodySystem(const Scene& scene, int rank);
  ~RigidBodySystem();

  /// Steps the zone's bodies by dt, pushing the ghosts of higher ranks' bodies as well, and
  /// writes their state back; returns how many are awake.
  std::size_t step(EntityStore& store, const GhostStore* ghosts, double dt);
  /// What the last step did to other zones' bodies (to send to their owners).
  const std::vector<GhostImpulse>& ghostImpulses() const { return ghost_impulses_; }
  /// Adds velocity changes other zones computed for this zone's bodies (wakes them).
  void applyImpulses(EntityStore& store, const std::vector<GhostImpulse>& in);
  /// Bodies whose state went non-finite (frozen by the engine), since the start.
  std::uint64_t quarantined() const { return quarantined_; }
  /// Times the engine's world was rebuilt because bodies came or went.
  std::uint64_t rebuilds() const { return rebuilds_; }

 private:
  void rebuild(const EntityStore& store, const GhostStore* ghosts,
               const std::vector<std::size_t>& foreign);
  /// Ghost indices of the bodies whose contacts with ours this zone resolves, in id order.
  std::vector<std::size_t> foreignBodies(const GhostStore* ghosts) const;

  const Scene& scene_;
  int rank_;
  std::unique_ptr<physics::World> world_;
  std::vector<EntityId> body_entity_;  // dynamic body index - first_dynamic_ -> entity
  std::uint32_t first_dynamic_ = 0;    // the static ground and walls come first
  IdSetDigest members_;
  std::vector<EntityId> foreign_entity_;  // foreign bodies, after the zone's own
  std::vector<GhostImpulse> ghost_impulses_;
  std::uint64_t quarantined_ = 0;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace zonesim::zone
