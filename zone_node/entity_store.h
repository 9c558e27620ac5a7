#pragma once
// The zone's entities as dense arrays, one per component, indexed 0..size()-1.
// Removal swaps the last entity into the hole, so indices are not stable across a tick's
// migrations: hold EntityIds, and look them up with indexOf().

#include <array>
#include <cstdint>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <variant>
#include <vector>

#include "common/entity_id.h"
#include "common/math.h"
#include "crowd/ant_trip.h"
#include "zone_node/net/dead_reckoning_state.h"

namespace zonesim::zone {

/// Item: a unique thing lying on the ground, taken by whoever its owner decides
/// (systems/interactions.h).
enum class EntityKind : std::uint8_t { Npc = 0, Avatar = 1, RigidBody = 2, Emitter = 3, Item = 4 };
constexpr int kEntityKindCount = 5;

/// A formation member's own state (systems/formation_movement.h: crowd::MemberState).
struct FormationMemberData {
  std::int32_t mode = 0;                ///< crowd::MemberMode
  std::int32_t path_at = 0;             ///< index (in cells) of the next cell of `path`
  double planned_x = 0, planned_z = 0;  ///< the centre the rejoin path was planned to
  std::vector<std::int32_t> path;       ///< the rejoin path's cells as x, y pairs

  bool operator==(const FormationMemberData&) const = default;
};

/// An ant's own state (systems/ant_movement.h): its trip, crowd/'s colony rule's data.
using AntData = crowd::AntTrip;

/// A road traveller's own state (systems/road_movement.h).
struct RoadTripData {
  std::int32_t next_node = 0;  ///< the node it walks to
  std::int32_t goal = 0;       ///< the node it travels to

  bool operator==(const RoadTripData&) const = default;
};

/// The per-system state of an NPC that a crowd system moves (none for wanderers, flocks and
/// flow crowds, whose state is their position and velocity).
using CrowdState = std::variant<std::monostate, FormationMemberData, AntData, RoadTripData>;

/// Walking NPC: waypoint wandering.
struct NpcData {
  Vec3 waypoint = Vec3::Zero();
  double max_speed = 1.0;
  double accel = 2.0;
  double waypoint_radius = 30.0;
  double arrive_distance = 1.0;
  double separation_radius = 0;      ///< keeps this far from other walkers (0: walks through them)
  double separation_weight = 1;      ///< strength of the push, in top speeds at contact
  Vec3 gather_point = Vec3::Zero();  ///< the population's gathering (NpcPopulation::Gather)
  double gather_radius = 0;          ///< 0: never gathers
  double gather_start = 0, gather_end = 0;  ///< simulated seconds
  bool gathering = false;                   ///< the current waypoint is one of the gathering's
  /// Its population's index in Scene::npcs when a crowd system moves it (a flock, a flow
  /// crowd, a formation, a colony or a road network: the population says which), else -1 (a
  /// wanderer).
  std::int32_t population = -1;
  /// The state of its own that the crowd system keeps for it, carried by migration like an
  /// agent's path: one type per system, so no field means different things to different ones.
  CrowdState crowd;

  bool operator==(const NpcData&) const = default;
};

/// The NPC's crowd state of type T, made afresh if it holds none (or another system's).
template <typename T>
T& crowdState(NpcData& n) {
  if (!std::holds_alternative<T>(n.crowd)) n.crowd.template emplace<T>();
  return std::get<T>(n.crowd);
}

/// A player's avatar, driven by inputs applied exactly once by sequence number.
struct AvatarData {
  std::uint64_t player_id = 0;
  std::uint32_t last_input_seq = 0;
  float move_x = 0, move_z = 0;
  double max_speed = 5.0;
  bool announced = false;  ///< its owner told the gateways (creation announced)
  std::uint8_t kind = 0;   ///< the player's kind (common/player_kind.h)
  double height = 0;       ///< metres above the ground a flyer holds; 0: it walks on the ground
  /// The player's last transaction handed to the ledger in sequence order (zone_node/
  /// transactions.h): the zone that owns the avatar next goes on from it.
  std::uint32_t last_transaction_seq = 0;

  bool operator==(const AvatarData&) const = default;
};

/// A rigid body simulated by physics/.
/// One point of a cached contact: where it was, its narrowphase feature, and its normal and
/// two tangent impulses (physics::BodyContact).
struct CachedContactPoint {
  Vec3 position = Vec3::Zero();
  std::uint32_t feature = 0;
  std::array<double, 3> impulse{};

  bool operator==(const CachedContactPoint&) const = default;
};

/// Where a contact's manifold was computed, for contact recycling (physics/contact_recycling.h):
/// the normal, the poses of the contact's first and second body then, each point and its depth
/// then, and the pair's materials. Carried so that a world rebuilt on any rank recycles as the
/// old one would have.
struct CachedContactOrigin {
  Vec3 normal = Vec3::UnitY();
  Vec3 first_position = Vec3::Zero(), second_position = Vec3::Zero();
  Quat first_orientation = Quat::Identity(), second_orientation = Quat::Identity();
  std::vector<Vec3> points;  ///< as many as the contact's points
  std::vector<double> depths;
  double friction = 0, restitution = 0, rolling = 0;

  bool operator==(const CachedContactOrigin& o) const {
    return normal == o.normal && first_position == o.first_position &&
           second_position == o.second_position &&
           first_orientation.coeffs() == o.first_orientation.coeffs() &&
           second_orientation.coeffs() == o.second_orientation.coeffs() && points == o.points &&
           depths == o.depths && friction == o.friction && restitution == o.restitution &&
           rolling == o.rolling;
  }
};

/// A contact's impulses, kept for the next step's warm start. A body keeps those of its contacts
/// with bodies of higher id and with the world's static bodies, so they migrate with it and
/// reach whichever rank solves its island next (zone_node/systems/body_islands.h).
struct CachedContact {
  EntityId other;                ///< the other body (the higher id); none when world_body >= 0
  std::int32_t world_body = -1;  ///< else the static body touched: ground, wall or set piece
  std::uint16_t piece_self = 0, piece_other = 0;  ///< the pieces touching (compound parts)
  std::vector<CachedContactPoint> points;         ///< 1 to 4
  std::array<double, 2> rolling_impulse{};
  std::optional<CachedContactOrigin> origin;  ///< while the scene recycles contacts

  bool operator==(const CachedContact&) const = default;
};

/// A joint's impulses, kept for the next step's warm start by its first dynamic body.
struct CachedJoint {
  std::int32_t joint = -1;       ///< the scene's joint (physics.joints index)
  std::vector<double> impulses;  ///< physics::World's joint warm start (1 or 11 values)

  bool operator==(const CachedJoint&) const = default;
};

struct BodyData {
  /// A compound's parts are not carried: it is a named scene body (physics.bodies), and each
  /// zone builds its shape from the scene by the entity's id.
  enum Shape : std::uint8_t { Sphere = 0, Box = 1, Capsule = 2, Compound = 3 };
  double radius = 0.5;  ///< sphere and capsule
  double mass = 1.0;
  double restitution = 0.5;
  Vec3 angular_velocity = Vec3::Zero();
  bool sleeping = false;
  std::uint8_t shape = Sphere;
  Vec3 half_extents = Vec3::Constant(0.5);  ///< box
  double half_height = 0.5;                 ///< capsule: half the inner segment, local y
  double friction = 0.5;
  double linear_damping = 0;   ///< 1/s (physics::BodyDesc)
  double angular_damping = 0;  ///< 1/s
  double rolling_resistance = 0;  ///< c_rr (physics::BodyDesc)
  // Carried so that a rank solving the body's island steps it exactly as one world would:
  double rest_time = 0;                 ///< s the body has rested (physics::SleepState)
  EntityId sleep_group;                 ///< asleep: the lowest id of the island it fell asleep with
  std::vector<CachedContact> contacts;  ///< warm starts (CachedContact)
  std::vector<CachedJoint> joints;      ///< warm starts of the joints it holds
  std::int32_t step_lag = 0;            ///< ticks held by level of detail, still owed (StepLod)

  bool operator==(const BodyData&) const = default;
};

/// A particle emitter; its particles are zone-local effects (see systems/emitters.h).
struct EmitterData {
  double rate = 100;
  double lifetime = 2;
  double speed = 5;
  double spawn_accumulator = 0;
  double drag = 0.1;
  double restitution = 0.4;
  int max_particles = 4096;

  bool operator==(const EmitterData&) const = default;
};

/// An AI agent's own state (zone_node/systems/agent_*.h); travels with the entity on migration,
/// so a behaviour continues on the next zone exactly as it would have on this one.
struct AgentData {
  static constexpr int kLevels = 8;    ///< nesting depth of machine states kept
  static constexpr int kMaxPlan = 16;  ///< GOAP actions kept
  std::int32_t type = -1;              ///< index in Scene::agents.types; -1: not an agent
  std::int32_t state = 0;              ///< machine leaf state (fsm, guard)
  std::int32_t step = 0;               ///< machine steps taken
  std::int32_t entered[kLevels] = {};  ///< step at which each level of the state was entered
  std::int32_t action = 0;             ///< AgentAction chosen last tick
  std::int32_t transitions = 0;        ///< machine transitions so far
  double health = 100, energy = 100;   ///< needs, 0..100
  double speed_factor = 1;             ///< fuzzy: blended speed over the type's top speed
  double approach = 0;                 ///< fuzzy: -1 away from the enemy .. 1 toward it
  // GOAP: the plan made at the start, executed step by step.
  std::uint64_t facts = 0;           ///< world facts as the agent believes them
  std::int32_t plan[kMaxPlan] = {};  ///< action indices
  std::int32_t plan_length = -1;     ///< -1: not planned yet
  std::int32_t plan_step = 0;        ///< next action to do
  double action_time = 0;            ///< seconds spent at the current action's place
  double plan_cost = 0;              ///< summed cost of the actions done
  // Travel: goal, the path (cells of the scene's map) and progress along its spline.
  std::int32_t goal = 0;  ///< index of the current goal in the type's list
  std::int32_t nav = 0;   ///< AgentNav: 0 none, 1 waiting, 2 moving, 3 arrived, 4 no path
  double dwell = 0;       ///< seconds spent at the reached goal
  double origin_x = 0, origin_z = 0;  ///< where the current path starts (its first point)
  double target_x = 0, target_z = 0;  ///< where it ends
  double travelled = 0;               ///< arc length walked along the path's spline
  std::uint64_t asked_tick = 0;       ///< tick the waiting path request was made (its age)
  std::int32_t replans = 0;           ///< paths requested again after a door cut them
  std::int32_t arrivals = 0;          ///< goals reached
  /// x, y pairs, empty when not moving: the path's cells, or with `map.navigation: navmesh`
  /// its end cells with the mesh corners (lattice points of the map) between them.
  std::vector<std::int32_t> path;
  // What it perceived when it last decided: with agents.decide_every > 1 it acts on this
  // between decisions (agent_senses.h).
  bool enemy_seen = false;
  double enemy_x = 0, enemy_z = 0;  ///< nearest enemy then, when one was seen
  double enemy_distance = 1e9;      ///< kNoEnemy when none was

  bool operator==(const AgentData&) const = default;
};

/// What the scene's interactions (systems/interactions.h) keep per entity: its health, the
/// kills its victims' owners confirmed, its items, and the numbering of the messages it posts
/// (cluster/entity_mail.h: (id, mail_seq) names each one, across migrations and restarts).
struct CombatData {
  double health = 100;          ///< 0..100; a hit that takes it to 0 kills, and it starts again
  std::uint32_t kills = 0;      ///< hits that killed, as the victim's owner confirmed
  std::uint32_t deaths = 0;     ///< times it was killed
  std::int32_t items = 0;       ///< items it holds (avatars hand them to each other)
  std::uint32_t mail_seq = 0;   ///< messages it posted
  /// An item granted to a claimant: 1 + the tick it was decided in (0: not taken). It leaves
  /// the world once a checkpoint holds the decision, so no restart can undo what clients saw.
  std::uint64_t taken_at = 0;

  bool operator==(const CombatData&) const = default;
};

/// One entity with all its components, for creation and migration.
struct EntityRecordData {
  EntityId id;
  EntityKind kind = EntityKind::Npc;
  Vec3 pos = Vec3::Zero();
  Vec3 vel = Vec3::Zero();
  Quat rot = Quat::Identity();
  std::uint64_t rng_state = 0;
  NpcData npc;
  AvatarData avatar;
  BodyData body;
  EmitterData emitter;
  AgentData agent;
  CombatData combat;
};

class EntityStore {
 public:
  std::size_t size() const { return id.size(); }
  std::size_t count(EntityKind k) const { return kind_count_[std::size_t(k)]; }
  /// Changes whenever an entity is added or removed, to a value no store of this process had
  /// before (a system that found nothing to do can tell that its entities are still the ones
  /// it looked at without looking again, even if its store was replaced).
  std::uint64_t membership() const { return membership_; }

  /// Appends an entity; the id must not be present.
  std::size_t add(const EntityRecordData& r);
  /// Removes the entity at index i by moving the last one into its place.
  void removeAt(std::size_t i);
  /// Copies the entity at index i out, with all its components.
  EntityRecordData record(std::size_t i) const;
  std::optional<std::size_t> indexOf(EntityId e) const;
  /// The avatar of a player, if this zone owns it.
  std::optional<std::size_t> avatarOf(std::uint64_t player_id) const;

  // Dense component arrays (public: systems iterate them directly).
  std::vector<EntityId> id;
  std::vector<EntityKind> kind;
  std::vector<Vec3> pos;
  std::vector<Vec3> vel;
  std::vector<Quat> rot;
  std::vector<std::uint64_t> rng_state;
  std::vector<NpcData> npc;
  std::vector<AvatarData> avatar;
  std::vector<BodyData> body;
  std::vector<EmitterData> emitter;
  std::vector<AgentData> agent;  ///< type -1 for entities that are not AI agents
  std::vector<CombatData> combat;
  std::vector<DeadReckoningState> dr;

 private:
  std::unordered_map<std::uint64_t, std::size_t> index_of_;  // lookups only, never iterated
  std::unordered_map<std::uint64_t, std::size_t> avatar_of_player_;
  std::size_t kind_count_[kEntityKindCount] = {};
  std::uint64_t membership_ = 0;
};

/// One per-entity column: the store's array and the record's field it holds. The two members
/// are template arguments, so code keyed on a column (the migration codec's schema field, the
/// dump's choice of columns) picks it by the column's type, at compile time.
template <auto Store, auto Record>
struct EntityColumn {
  static constexpr auto store = Store;
  static constexpr auto record = Record;
  const char* name;
};

/// Every column an entity record carries, in the schema's order. This one list drives add,
/// remove and record (entity_store.cpp), the migration and checkpoint codec
/// (cluster/entity_codec.cpp: one SchemaField per column, a compile error if one is missing) and
/// the state dump (state_dump.cpp), as kCounterFields drives the metrics: a new per-entity field
/// is one line here plus its field in idl/entity_record.fbs and its SchemaField. (`dr`, the
/// publisher's memory of what it sent, is the store's own and never migrates.)
inline constexpr auto kEntityColumns =
    std::tuple{EntityColumn<&EntityStore::id, &EntityRecordData::id>{"id"},
               EntityColumn<&EntityStore::kind, &EntityRecordData::kind>{"kind"},
               EntityColumn<&EntityStore::pos, &EntityRecordData::pos>{"pos"},
               EntityColumn<&EntityStore::vel, &EntityRecordData::vel>{"vel"},
               EntityColumn<&EntityStore::rot, &EntityRecordData::rot>{"rot"},
               EntityColumn<&EntityStore::rng_state, &EntityRecordData::rng_state>{"rng_state"},
               EntityColumn<&EntityStore::npc, &EntityRecordData::npc>{"npc"},
               EntityColumn<&EntityStore::avatar, &EntityRecordData::avatar>{"avatar"},
               EntityColumn<&EntityStore::body, &EntityRecordData::body>{"body"},
               EntityColumn<&EntityStore::emitter, &EntityRecordData::emitter>{"emitter"},
               EntityColumn<&EntityStore::agent, &EntityRecordData::agent>{"agent"},
               EntityColumn<&EntityStore::combat, &EntityRecordData::combat>{"combat"}};

/// Calls f(column) for every column of kEntityColumns, in order.
template <typename F>
void forEachEntityColumn(F&& f) {
  std::apply([&](const auto&... column) { (f(column), ...); }, kEntityColumns);
}

}  // namespace zonesim::zone
