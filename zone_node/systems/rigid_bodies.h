#pragma once
// The zone's rigid bodies on the physics engine (physics/): spheres, boxes, capsules and
// compounds of them (named scene bodies, whose parts every zone builds from the scene) on a
// static ground and inside the world's walls. The engine's world persists across ticks
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
//
// The scene's hand-placed objects (physics.bodies, joints, cloths, explosions): joints are
// added to the engine's world whenever it is rebuilt, with anchors fixed from the scene's
// start poses; cloths are zone-local mass-spring patches stepped after the bodies and colliding
// with them (and the ground and walls) both ways; explosions act on this zone's own bodies
// only (never on ghosts, whose owners apply them), an impulse in the first tick starting at or
// after its time, a blast as a per-tick impulse F f(r) dt for as long as it lasts. The loader
// allows joints and cloths only on a single zone. Static and kinematic scene bodies are set
// pieces (set_pieces.h) that every zone places in its world after the ground and walls.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "common/entity_id.h"
#include "common/math.h"
#include "crowd/vec2.h"
#include "physics/shape.h"
#include "physics/step_profile.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/set_pieces.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::physics {
class World;
class Cloth;
class ClothColliders;
}  // namespace zonesim::physics

namespace zonesim::zone {

class RigidBodySystem : public ZoneSystem {
 public:
  /// `rank`: this zone's rank, which decides whose contacts across a border it resolves.
  RigidBodySystem(const Scene& scene, int rank);
  ~RigidBodySystem();

  /// Created when the zone first holds a body or the scene has cloths: active from then on.
  bool active() const override { return true; }
  /// Steps the zone's bodies (and cloths) by one tick, pushing the ghosts of higher ranks'
  /// bodies as well, and writes their state back; counts the awake bodies. The tick times the
  /// explosions and kinematic set pieces.
  void step(StepContext& ctx) override;
  /// Time of each engine stage in the last step (zero when the world did not step).
  const physics::StepProfile& profile() const { return profile_; }
  /// The scene's cloths, in scene order.
  std::size_t clothCount() const { return cloths_.size(); }
  /// Cloth i as stepped so far.
  const physics::Cloth& cloth(std::size_t i) const { return *cloths_[i]; }
  /// Sub-steps cloth i takes per tick.
  int clothSubsteps(std::size_t i) const { return cloth_substeps_[i]; }
  /// Joints in the engine's world (those of the scene whose bodies this zone holds).
  std::size_t joints() const { return joints_added_; }
  /// What the last step did to other zones' bodies (to send to their owners).
  const std::vector<GhostImpulse>& ghostImpulses() const { return ghost_impulses_; }
  /// Adds velocity changes other zones computed for this zone's bodies (wakes them).
  void applyImpulses(EntityStore& store, const std::vector<GhostImpulse>& in);
  /// Bodies whose state went non-finite (frozen by the engine), since the start.
  std::uint64_t quarantined() const { return quarantined_; }
  /// Times the engine's world was rebuilt because bodies came or went.
  std::uint64_t rebuilds() const { return rebuilds_; }

 private:
  /// Returns how many bodies are awake.
  std::size_t advance(EntityStore& store, const GhostStore* ghosts, double dt, std::uint64_t tick,
                      std::span<const crowd::Vec2> players);
  /// Level of detail: this zone's bodies beyond lod.near_radius of every player step every
  /// lod.physics_every ticks (their islands do, unless a near body is in them).
  void setStepPeriods(std::span<const crowd::Vec2> players);
  void rebuild(const EntityStore& store, const GhostStore* ghosts,
               const std::vector<std::size_t>& foreign);
  /// Ghost indices of the bodies whose contacts with ours this zone resolves, in id order.
  std::vector<std::size_t> foreignBodies(const GhostStore* ghosts) const;
  /// The engine body of an entity's (or ghost's) rigid-body record.
  physics::BodyDesc descOf(EntityId id, const BodyData& b, const Vec3& pos, const Quat& rot,
                           const Vec3& vel) const;
  /// Adds the scene's joints whose bodies this world holds.
  void addJoints();
  /// Applies the scene's explosions due in tick k to this zone's bodies; true if any acted.
  bool explode(std::uint64_t k, double dt);
  /// Steps every cloth by dt against the world's bodies.
  void stepCloths(double dt);

  const Scene& scene_;
  int rank_;
  std::unique_ptr<physics::World> world_;
  std::vector<EntityId> body_entity_;  // dynamic body index - first_dynamic_ -> entity
  std::uint32_t first_dynamic_ = 0;    // the static ground, walls and set pieces come first
  SetPieces set_pieces_;
  // The dynamic compound bodies by entity id (records do not carry parts): the shape, centred,
  // and its volume (mass / volume is the density the engine takes).
  struct Compound {
    physics::Shape shape;
    double volume = 0;
  };
  std::map<EntityId, Compound> compounds_;
  IdSetDigest members_;
  std::vector<EntityId> foreign_entity_;  // foreign bodies, after the zone's own
  std::vector<GhostImpulse> ghost_impulses_;
  std::uint64_t quarantined_ = 0;
  std::uint64_t rebuilds_ = 0;
  std::uint64_t world_steps_ = 0;  // times the engine's world stepped
  std::uint64_t bodies_held_ = 0;  // of this zone's bodies, held still in the last step (lod)
  physics::StepProfile profile_;
  std::size_t joints_added_ = 0;
  std::vector<std::unique_ptr<physics::Cloth>> cloths_;
  std::vector<int> cloth_substeps_;
  std::unique_ptr<physics::ClothColliders> cloth_colliders_;
};

}  // namespace zonesim::zone
