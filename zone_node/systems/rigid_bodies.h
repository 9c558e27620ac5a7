#pragma once
// The zone's rigid bodies on the physics engine (physics/): spheres, boxes, capsules and
// compounds of them (named scene bodies, whose parts every zone builds from the scene) on a
// static ground and inside the world's walls. The engine's world persists across ticks
// (warm starting, islands, sleeping) and is rebuilt from the entity store only when the zone's
// set of bodies changes (a body migrated in or out), which costs that tick its warm start.
// A zone whose bodies all sleep skips the step entirely.
//
// Contacts across zone borders are solved exactly: on several ranks, every island of bodies that
// may touch this tick is stepped whole by one rank, the owner of its lowest id, which gathers
// the island's bodies from their owners and sends their new state back (body_islands.h). Each
// body carries what its next step needs from the last (rest time, sleep, and the impulses of
// its contacts for the warm start), so a world rebuilt around other bodies steps it as the old
// one would have: the cluster ends bit for bit where one zone holding every body would.
//
// The scene's hand-placed objects (physics.bodies, joints, cloths, explosions): joints are
// added to the engine's world whenever it is rebuilt, with anchors fixed from the scene's
// start poses; cloths are zone-local mass-spring patches stepped after the bodies and colliding
// with them (and the ground and walls) both ways; explosions act on the bodies of the
// world that steps them (each body once in the cluster), an impulse in the first tick starting at
// or after its time, a blast as a per-tick impulse F f(r) dt for as long as it lasts. The loader
// allows joints and cloths only on a single zone. Static and kinematic scene bodies are set
// pieces (set_pieces.h) that every zone places in its world after the ground and walls.

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <unordered_set>
#include <vector>

#include "common/entity_id.h"
#include "common/math.h"
#include "crowd/vec2.h"
#include "physics/shape.h"
#include "physics/step_profile.h"
#include "zone_node/entity_store.h"
#include "zone_node/systems/body_islands.h"
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
  /// Steps the zone's bodies (and cloths) by one tick and writes their state back; counts the
  /// awake bodies. In a cluster (ctx.cluster.swap set) it first trades bodies so that each
  /// island is stepped by the rank solving it (collective: every rank calls it every tick).
  /// The tick times the explosions and kinematic set pieces.
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
  /// Seconds the last step spent sharing islands and trading bodies with other ranks.
  double borderTime() const { return border_time_; }
  /// Bodies whose state went non-finite (frozen by the engine), since the start.
  std::uint64_t quarantined() const { return quarantined_; }
  /// Times the engine's world was rebuilt because bodies came or went.
  std::uint64_t rebuilds() const { return rebuilds_; }

 private:
  /// A body the engine's world holds: a row of the zone's store, or of visitors_ (another
  /// zone's body, here for an island this zone solves).
  struct BodyRef {
    EntityStore* store;
    std::size_t index;
    EntityId id() const { return store->id[index]; }
  };
  // The world's joints: the scene's index, the kind, the engine's index among that kind, and
  // the body that keeps its warm start in its record (cluster).
  struct JointSlot {
    int scene;
    int type;  // SceneJoint::Type
    std::uint32_t index;
    physics::BodyIndex holder;
  };
  /// The store's rigid bodies, by id.
  static std::vector<std::size_t> bodiesById(const EntityStore& store);
  /// The lone zone's step: all of its bodies in one world. Returns how many are awake.
  std::size_t advanceAlone(StepContext& ctx);
  /// The cluster's step (rigid_bodies_cluster.cpp): trades bodies, steps this zone's islands,
  /// sends the visitors back. Returns how many of the bodies it stepped are awake.
  std::size_t advanceInCluster(StepContext& ctx);
  /// Rebuilds the world around `bodies` (id order) unless it holds exactly them already;
  /// `carried`: take each body's sleep and warm starts from its record.
  void holdBodies(const std::vector<BodyRef>& bodies, bool carried);
  /// Poses the set pieces, fires explosions and steps the world and cloths; returns whether
  /// the world stepped.
  bool stepWorld(StepContext& ctx);
  /// Writes the world's state back to the bodies' rows; `carried`: with sleep and warm starts.
  /// Returns how many are awake.
  std::size_t writeBack(const std::vector<BodyRef>& bodies, bool carried);
  /// The bodies' warm starts, from their records into the world (rigid_bodies_cluster.cpp).
  void importCarried(const std::vector<BodyRef>& bodies);
  /// The world's sleep and warm starts into the bodies' records (rigid_bodies_cluster.cpp).
  void exportCarried(const std::vector<BodyRef>& bodies);
  /// A joint's warm start in the world, and back (rigid_bodies_cluster.cpp).
  std::vector<double> jointWarmStart(const JointSlot& slot) const;
  void setJointWarmStart(const JointSlot& slot, const std::vector<double>& values);
  /// In a cluster the cloths live on one rank (the zone holding the first cloth's first
  /// particle at the start, decided at the first step): there, each cloth's reach box, as an
  /// island whose label is below every id, so the bodies it may touch are solved there.
  std::vector<BorderBody> clothBoxes(const StepContext& ctx);
  /// Whether this zone steps the cloths: alone, or the cluster's cloth rank.
  bool holdsCloths(const StepContext& ctx) const {
    return !cloths_.empty() && (cloth_rank_ < 0 || cloth_rank_ == ctx.cluster.rank);
  }
  /// Level of detail: this zone's bodies beyond lod.near_radius of every player step every
  /// lod.physics_every ticks (their islands do, unless a near body is in them).
  void setStepPeriods(std::span<const crowd::Vec2> players);
  void rebuild(const std::vector<BodyRef>& bodies);
  /// The engine shape of an entity's rigid-body record.
  physics::Shape shapeOf(EntityId id, const BodyData& b) const;
  /// The engine body of an entity's rigid-body record.
  physics::BodyDesc descOf(EntityId id, const BodyData& b, const Vec3& pos, const Quat& rot,
                           const Vec3& vel) const;
  /// Adds the scene's joints whose bodies this world holds.
  void addJoints();
  /// Applies the scene's explosions due in tick k to the world's bodies; true if any acted.
  bool explode(std::uint64_t k, double dt);
  /// Whether some explosion acts in tick k.
  bool explosionDue(std::uint64_t k, double dt) const;
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
  EntityStore visitors_;               // other zones' bodies in this tick's islands (cluster)
  std::vector<BodyLink> joint_links_;  // jointed pairs of dynamic bodies: one island
  std::unordered_set<std::uint64_t> jointed_;  // their ids
  int cloth_rank_ = -1;                        // the rank stepping the cloths (cluster)
  double border_time_ = 0;
  std::uint64_t quarantined_ = 0;
  std::uint64_t rebuilds_ = 0;
  std::uint64_t world_steps_ = 0;  // times the engine's world stepped
  std::uint64_t bodies_held_ = 0;  // of this zone's bodies, held still in the last step (lod)
  // The store's membership when advanceAlone last found every body asleep and did not step.
  std::optional<std::uint64_t> resting_membership_;
  physics::StepProfile profile_;
  std::size_t joints_added_ = 0;
  std::vector<JointSlot> joint_slots_;
  std::vector<std::unique_ptr<physics::Cloth>> cloths_;
  std::vector<int> cloth_substeps_;
  std::unique_ptr<physics::ClothColliders> cloth_colliders_;
};

}  // namespace zonesim::zone
