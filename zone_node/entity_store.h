#pragma once
// The zone's entities as dense arrays, one per component, indexed 0..size()-1.
// Removal swaps the last entity into the hole, so indices are not stable across a tick's
// migrations: hold EntityIds, and look them up with indexOf().

#include <array>
#include <cstdint>
#include <optional>
#include <unordered_map>
#include <vector>

#include "common/entity_id.h"
#include "common/math.h"
#include "idl/dr_model.h"

namespace zonesim::zone {

enum class EntityKind : std::uint8_t { Npc = 0, Avatar = 1, RigidBody = 2, Emitter = 3 };
constexpr int kEntityKindCount = 4;

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
  /// Its population's index in Scene::npcs when a crowd system moves it (a flock or a flow
  /// crowd: the population says which), else -1 (a wanderer).
  std::int32_t flock = -1;
};

/// A player's avatar, driven by inputs applied exactly once by sequence number.
struct AvatarData {
  std::uint64_t player_id = 0;
  std::uint32_t last_input_seq = 0;
  float move_x = 0, move_z = 0;
  double max_speed = 5.0;
  bool announced = false;  ///< its owner told the gateways (creation announced)
};

/// A rigid body simulated by zone_node/physics.
struct BodyData {
  enum Shape : std::uint8_t { Sphere = 0, Box = 1, Capsule = 2 };
  double radius = 0.5;  ///< sphere and capsule
  double mass = 1.0;
  double restitution = 0.5;
  Vec3 angular_velocity = Vec3::Zero();
  bool sleeping = false;
  std::uint8_t shape = Sphere;
  Vec3 half_extents = Vec3::Constant(0.5);  ///< box
  double half_height = 0.5;                 ///< capsule: half the inner segment, local y
  double friction = 0.5;
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
};

/// What the publish phase last told subscribers about the entity (sender-side dead reckoning).
struct DeadReckoningState {
  int cell = -1;    ///< interest cell it was last published in; -1 = never published here
  dr::State sent;   ///< the quantised state receivers hold
  double time = 0;  ///< sim time `sent` was sampled
  /// Velocities of the last ticks (oldest first once full): the acceleration estimate's window.
  static constexpr int kVelocityWindow = 6;
  std::array<Vec3, kVelocityWindow> vel_history{};
  int vel_count = 0;                 ///< how many of vel_history hold a tick (up to the window)
  int vel_next = 0;                  ///< where the next tick's velocity goes
  Quat last_rot = Quat::Identity();  ///< previous tick's orientation (angular velocity estimate)
  bool has_last = false;
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
};

class EntityStore {
 public:
  std::size_t size() const { return id.size(); }
  std::size_t count(EntityKind k) const { return kind_count_[std::size_t(k)]; }

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
  std::vector<DeadReckoningState> dr;

 private:
  std::unordered_map<std::uint64_t, std::size_t> index_of_;  // lookups only, never iterated
  std::unordered_map<std::uint64_t, std::size_t> avatar_of_player_;
  std::size_t kind_count_[kEntityKindCount] = {};
};

}  // namespace zonesim::zone
