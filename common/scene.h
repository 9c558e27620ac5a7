#pragma once
// A scene: everything a run needs to know about the world, loaded from a YAML file.
// Plain data only; loadScene() validates every field and reports file:line: field: problem.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace zonesim {

/// Plain 3-vector for scene data (keeps Eigen out of this widely included header).
struct SceneVec3 {
  double x = 0, y = 0, z = 0;
};

/// An axis-aligned box, y up; the ground plane is x-z.
struct SceneBox {
  SceneVec3 min, max;
};

/// How the ground plane is split among zone ranks.
struct ZoneLayout {
  /// Grid: even columns x rows. Rcb: the same shape, with column and row boundaries placed by
  /// recursive coordinate bisection so each zone starts with an equal share of the entities.
  enum class Kind { Grid, Rcb };
  Kind kind = Kind::Grid;
  int columns = 1;  ///< zones along x
  int rows = 1;     ///< zones along z
};

/// Reynolds flocking for an NPC population (zone_node/crowd/flock.h, docs/crowd.md).
struct NpcFlock {
  bool enabled = false;            ///< the population flocks instead of wandering
  double radius = 3.0;             ///< m: alignment and cohesion see neighbours this close
  double separation_radius = 1.0;  ///< m: pushed apart closer than this
  double separation_weight = 20;   ///< 1/s^2 per unit of (radius / distance - 1)
  double alignment_weight = 1.0;   ///< 1/s: velocity follows the neighbours' mean velocity
  double cohesion_weight = 0.5;    ///< 1/s^2: pull toward the neighbours' centre
  double max_speed = 2.0;          ///< m/s
  double max_force = 8.0;          ///< m/s^2, bound on the steering acceleration
};

/// Walking NPCs wandering between random waypoints, or flocking (`flock`).
struct NpcPopulation {
  int count = 0;
  double min_speed = 1.0;  ///< m/s, each NPC draws its top speed in [min, max]
  double max_speed = 2.0;
  double acceleration = 2.0;     ///< m/s^2 toward the waypoint
  double waypoint_radius = 30;   ///< next waypoint drawn within this distance
  double arrive_distance = 1.0;  ///< waypoint counts as reached inside this distance
  SceneBox region;               ///< where they start (defaults to the world)
  double separation_radius = 0;  ///< keep this far from other walkers (0: no avoidance)
  double separation_weight = 1;  ///< push at contact, in top speeds
  /// A gathering: from start_s to end_s of simulated time every NPC of the population heads for
  /// waypoints within `radius` of `point` (x, z); before and after, it wanders (a crowd that
  /// converges, then disperses). radius 0: no gathering.
  struct Gather {
    double x = 0, z = 0, radius = 0, start_s = 0, end_s = 0;
  } gather;
  NpcFlock flock;  ///< flocking instead of waypoints when enabled
};

/// Spheres falling under gravity and bouncing on the ground (the physics issue adds shapes).
struct RigidBodyPopulation {
  enum class Shape { Sphere, Box, Capsule };
  int count = 0;
  Shape shape = Shape::Sphere;
  SceneVec3 size{1, 1, 1};  ///< box: full edge lengths (m)
  double length = 1.0;      ///< capsule: length of the inner segment, along local y (m)
  double friction = 0.5;
  double radius = 0.5;  ///< sphere and capsule radius (m)
  double mass = 1.0;
  double restitution = 0.5;
  double drop_height = 10.0;      ///< start gap between ground and body (lowest of the range)
  double max_drop_height = 10.0;  ///< start heights are drawn uniformly in [drop_height, this]
  SceneBox region;                ///< where they start on x-z (defaults to the world)
};

/// The rigid-body engine's approximations (zone_node/physics).
struct PhysicsSettings {
  enum class Integrator {
    ExplicitEuler,
    SemiImplicitEuler,
    PositionVerlet,
    VelocityVerlet,
    Rk2,
    Rk4
  };
  enum class Broadphase { BruteForce, SweepAndPrune, UniformGrid, AabbTree };
  /// Contact response (docs/physics.md compares them); same order as physics::SolverKind.
  enum class Solver { SoftStep, GaussSeidel, Sor, Jacobi, Penalty, Projection };
  Integrator integrator = Integrator::SemiImplicitEuler;
  Broadphase broadphase = Broadphase::SweepAndPrune;
  int substeps = 1;
  int velocity_iterations = 10;
  int position_iterations = 2;
  bool sleep = true;  ///< resting islands sleep and cost (almost) nothing
  Solver solver = Solver::GaussSeidel;
  double sor_omega = 1.3;  ///< over-relaxation factor of the sor solver
};

/// Particle emitters: each spawns `rate` particles per second with the given lifetime.
struct EmitterPopulation {
  int count = 0;
  double rate = 100;      ///< particles per second per emitter
  double lifetime = 2.0;  ///< seconds
  double speed = 5.0;     ///< initial speed, m/s, upward cone
  double restitution = 0.4;
  double drag = 0.1;         ///< linear drag coefficient, 1/s
  int max_particles = 4096;  ///< per emitter; the oldest are recycled first
  SceneBox region;           ///< where the emitters stand (defaults to the world)
};

/// Defaults for simulated players attached by client_stub.
struct ClientProfile {
  int players = 32;
  double speed = 5.0;           ///< m/s avatar walking speed
  double input_hz = 20;         ///< inputs per second per player
  double nimbus = 60;           ///< range of interest, metres
  double retarget_seconds = 8;  ///< how long a player walks toward one target before choosing anew
};

/// The dead-reckoning model of one entity type (DIS family, world frame).
struct DeadReckoningModel {
  /// Static: position only; First: + velocity; Second: + acceleration.
  enum class Order { Static, First, Second };
  Order order = Order::First;
  bool rotating = false;  ///< orientation extrapolated with the angular velocity, else fixed
};

/// Resolution and range of the quantised states sent to clients.
struct StateQuantisation {
  double position_resolution = 1.0 / 512;  ///< metres per step (relative to the interest cell)
  double max_speed = 64;                   ///< m/s, per axis
  double velocity_resolution = 1.0 / 128;  ///< m/s per step
  double max_acceleration = 64;            ///< m/s^2, per axis
  double acceleration_resolution = 1.0 / 32;
  double max_angular_velocity = 32;  ///< rad/s, per axis
  double angular_velocity_resolution = 1.0 / 256;
  int rotation_bits = 10;  ///< per smallest-three component
};

/// Sender-side dead reckoning: thresholds, heartbeat, and the model per entity type.
struct DeadReckoning {
  double position_threshold = 0.5;         ///< metres of prediction error before an update is sent
  double heartbeat_seconds = 5.0;          ///< an update at least this often per entity
  double orientation_threshold_deg = 3.0;  ///< degrees of orientation error before an update
  DeadReckoningModel npc;
  DeadReckoningModel avatar;
  DeadReckoningModel rigid_body{DeadReckoningModel::Order::Second, true};
  DeadReckoningModel emitter{DeadReckoningModel::Order::Static, false};
  StateQuantisation quantisation;
};

/// The seed's aura/nimbus rule: player A receives entity B's updates when A is inside B's aura
/// (range of influence, per entity type) and B inside A's nimbus (range of interest, per
/// player: clients.nimbus, grown with the player's speed up to max_nimbus).
struct AuraNimbus {
  double npc = 100;             ///< metres
  double avatar = 150;          ///< metres
  double rigid_body = 100;      ///< metres
  double emitter = 200;         ///< metres
  double nimbus_per_speed = 4;  ///< seconds: the nimbus grows by speed * this
  double max_nimbus = 150;      ///< metres: cap of the grown nimbus
};

/// The world's obstacle map: a Moving AI .map grid laid on the ground plane (`map:` key).
/// Column x runs along world x, row y along world z. Loaded by zone_node/world_map.h.
struct ObstacleMap {
  std::string file;      ///< path resolved against the scene file's folder; empty: no map
  double origin_x = 0;   ///< world x of the outer corner of cell (0, 0)
  double origin_z = 0;   ///< world z of the outer corner of cell (0, 0)
  double cell_size = 1;  ///< side of one cell, metres
  int line = 0;          ///< line of `map.file` in the scene (for errors found on loading)
  /// Whether the scene has a map.
  bool present() const { return !file.empty(); }
};

/// A whole scene; the docs for every key are in docs/scene-format.md.
struct Scene {
  std::string name;
  std::string source_path;  ///< file it was loaded from; empty from parseScene()
  SceneBox world;
  double tick_rate = 30;  ///< ticks per second of wall time when running real-time
  double dt = 1.0 / 30;   ///< simulated seconds per tick
  std::uint64_t seed = 1;
  ZoneLayout zones;
  double interest_cell_size = 50;  ///< metres; one DDS partition per cell
  int keyframe_every = 90;         ///< ticks between per-cell keyframes
  double halo_width = 10;
  DeadReckoning dead_reckoning;
  PhysicsSettings physics;
  std::vector<NpcPopulation> npcs;
  std::vector<RigidBodyPopulation> rigid_bodies;
  std::vector<EmitterPopulation> emitters;
  ClientProfile clients;
  AuraNimbus aura_nimbus;  ///< keys in the interest section
  ObstacleMap map;         ///< walls and open ground for crowds and path finding
};

/// Radius of the sphere around a body's centre that holds its whole shape.
double boundingRadius(const RigidBodyPopulation& p);

/// A scene file problem; what() is "file:line: field: what is wrong".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Loads and validates a scene file; throws SceneError on the first problem.
Scene loadScene(const std::string& path);

/// Parses scene text (the name is used in error messages as the file).
Scene parseScene(const std::string& text, const std::string& name);

}  // namespace zonesim
