#pragma once
// The zone's rigid bodies on the physics engine (zone_node/physics): spheres, boxes and capsules
// on a static ground and inside the world's walls. The engine's world persists across ticks
// (warm starting, islands, sleeping) and is rebuilt from the entity store only when the zone's
// set of bodies changes (a body migrated in or out), which costs that tick its warm start.
// A zone whose bodies all sleep skips the step entirely. Contacts with bodies owned by other
// zones are not seen yet (that needs ghosts: issue 5).

#include <cstdint>
#include <memory>
#include <vector>

#include "common/entity_id.h"
#include "common/scene.h"
#include "zone_node/entity_store.h"

namespace zonesim::physics {
class World;
}

namespace zonesim::zone {

class RigidBodySystem {
 public:
  explicit RigidBodySystem(const Scene& scene);
  ~RigidBodySystem();

  /// Steps the zone's bodies by dt and writes their state back; returns how many are awake.
  std::size_t step(EntityStore& store, double dt);
  /// Bodies whose state went non-finite (frozen by the engine), since the start.
  std::uint64_t quarantined() const { return quarantined_; }
  /// Times the engine's world was rebuilt because bodies came or went.
  std::uint64_t rebuilds() const { return rebuilds_; }

 private:
  void rebuild(const EntityStore& store);

  const Scene& scene_;
  std::unique_ptr<physics::World> world_;
  std::vector<EntityId> body_entity_;  // dynamic body index - first_dynamic_ -> entity
  std::uint32_t first_dynamic_ = 0;    // the static ground and walls come first
  IdSetDigest members_;
  std::uint64_t quarantined_ = 0;
  std::uint64_t rebuilds_ = 0;
};

}  // namespace zonesim::zone
