#pragma once
// A scene: everything a run needs to know about the world, loaded from a YAML file.
// Plain data only; loadScene() validates every field and reports file:line: field: problem.

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/scene_ai.h"

namespace zonesim {

/// Plain 3-vector for scene data (keeps Eigen out of this widely included header).
struct SceneVec3 {
  double x = 0, y = 0, z = 0;
};

/// An axis-aligned box, y up; the ground plane is x-z.
struct SceneBox {
  SceneVec3 min, max;
};

/// The `zones:` key: how the ground plane is split among zone ranks (the class that holds the
/// split at run time is zone::ZoneLayout).
struct SceneZones {
  /// Grid: even columns x rows. Rcb: the same shape, with column and row boundaries placed by
  /// recursive coordinate bisection so each zone starts with an equal share of the entities.
  enum class Kind { Grid, Rcb };
  Kind kind = Kind::Grid;
  int columns = 1;  ///< zones along x
  int rows = 1;     ///< zones along z
};

/// Reynolds flocking for an NPC population (crowd/flock.h, docs/crowd.md).
struct NpcFlock {
  bool enabled = false;            ///< the population flocks instead of wandering
  double radius = 3.0;             ///< m: alignment and cohesion see neighbours this close
  double separation_radius = 1.0;  ///< m: pushed apart closer than this
  double separation_weight = 20;   ///< 1/s^2 per unit of (radius / distance - 1)
  double alignment_weight = 1.0;   ///< 1/s: velocity follows the neighbours' mean velocity
  double cohesion_weight = 0.5;    ///< 1/s^2: pull toward the neighbours' centre
  double max_speed = 2.0;          ///< m/s
  double max_force = 8.0;          ///< m/s^2, bound on the steering acceleration
  /// `goal`: a point the flock heads for; each flocker's goal velocity points at it at
  /// `goal_speed`, ramping down within `goal_slow_radius`, followed at `goal_weight`.
  bool has_goal = false;
  double goal_x = 0, goal_z = 0;  ///< the point on the ground plane
  double goal_weight = 1.0;       ///< 1/s: rate at which velocity follows the goal velocity
  double goal_speed = 0;          ///< m/s toward the point (the loader sets max_speed if unset)
  double goal_slow_radius = 5.0;  ///< m: the goal speed ramps down to 0 this close
};

/// A flow-field crowd (crowd/flow_crowd.h, docs/crowd.md): each NPC heads for one
/// of a few destinations on the scene's map, along a field computed once per destination.
struct NpcFlow {
  bool enabled = false;  ///< the population follows flow fields instead of wandering
  /// A goal on the ground plane; `line` is where the scene gives it (for errors on loading).
  struct Destination {
    double x = 0, z = 0;
    int line = 0;
  };
  std::vector<Destination> destinations;  ///< each NPC draws one from its id
  double max_speed = 2.0;                 ///< m/s
  double max_force = 10.0;                ///< m/s^2, bound on the steering acceleration
  double steer_rate = 4.0;                ///< 1/s: rate at which velocity follows the field
  double separation_radius = 0.6;         ///< m: pushed apart closer than this
  double separation_weight = 10.0;        ///< 1/s^2 per unit of (radius / distance - 1)
  double arrive_radius = 0.75;            ///< m from the goal cell's centre: arrived, stops
  double slow_radius = 2.0;               ///< m: speed ramps down this close to the goal
};

/// A point on the ground plane given in the scene; `line` is where (for errors on loading).
struct ScenePoint {
  double x = 0, z = 0;
  int line = 0;
};

/// A road network: NPCs travel between waypoints of a weighted graph along cheapest paths
/// (ai/waypoint_graph.h, zone_node/systems/road_movement.h).
struct NpcRoads {
  bool enabled = false;  ///< the population travels the graph instead of wandering
  struct Edge {
    int a = 0, b = 0;         ///< node indices
    double cost = 0;          ///< > 0; the straight length unless the scene gives one
    std::uint32_t flags = 0;  ///< bits of flag_names the edge needs (door, ladder...)
    bool one_way = false;     ///< a -> b only
  };
  /// An edge shut from `from` until `until` (simulated seconds).
  struct Closure {
    int edge = 0;
    double from = 0, until = 0;
  };
  std::vector<ScenePoint> nodes;
  std::vector<Edge> edges;
  std::vector<std::string> flag_names;  ///< bit i of a flag set is flag_names[i]
  std::uint32_t may_use = 0;            ///< flags these NPCs may pass
  std::vector<Closure> closures;
};

/// A fixed group (crowd/formation.h, docs/crowd.md): the population's NPCs hold
/// slots around a centre that walks a route on the scene's map; a member cut off from the
/// group plans A* back to it and rejoins (`populations[].formation`).
struct NpcFormation {
  bool enabled = false;             ///< the population is a formation instead of wanderers
  std::vector<ScenePoint> route;    ///< the centre starts at the first; A* between points
  int columns = 4;                  ///< slots per row across the heading; rows trail behind
  double spacing = 1.5;             ///< m between neighbouring slots
  double centre_speed = 1.5;        ///< m/s of the centre along its route
  double max_speed = 2.5;           ///< m/s of a member (above the centre's, to catch up)
  double max_force = 8.0;           ///< m/s^2, bound on a member's steering acceleration
  double steer_rate = 4.0;          ///< 1/s: rate at which velocity follows the desired one
  double slot_gain = 2.0;           ///< 1/s: desired velocity per metre of slot error
  double slow_radius = 3.0;         ///< m: the centre slows down this close to its last point
  double turn_rate = 3.0;           ///< 1/s: rate at which the heading follows the route
  double cut_off = 5.0;             ///< m from its slot: a member is cut off
  double rejoin = 1.0;              ///< m from a visible slot: a rejoining member rejoins
  double replan = 2.0;              ///< m the centre moves before a rejoin path is re-planned
  double separation_radius = 0.6;   ///< m: members closer than this push apart
  double separation_weight = 10.0;  ///< 1/s^2 per unit of (radius / distance - 1)
};

/// An ant colony (docs/crowd.md): the population's NPCs are ants walking the scene's map cell
/// by cell from a nest, sensing only the cells next to them, laying pheromone on their way back
/// from the food; trails evaporate (`populations[].colony`).
struct NpcColony {
  bool enabled = false;             ///< the population is an ant colony
  ScenePoint nest, food;            ///< where the ants start and what they look for
  double food_until = -1;           ///< s of simulated time the food is taken away (<0: never)
  double alpha = 1.0;               ///< weight of the pheromone in a step's choice
  double beta = 2.0;                ///< weight of the heuristic desirability of a step
  bool knows_food = true;           ///< eta uses the straight-line distance to the food
  double evaporation = 0.05;        ///< fraction of every trail lost per second
  double deposit = 1.0;             ///< Q: a returning ant lays Q / (route length) per cell
  double exploitation = 0.0;        ///< q0: chance of taking the strongest step outright
  double initial_pheromone = 0.01;  ///< trail on every cell at the start
  double speed = 2.0;               ///< m/s of an ant
  int max_steps = 0;                ///< cells before a searching ant gives up (0: 4 x open cells)
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
  NpcFlock flock;          ///< flocking instead of waypoints when enabled
  NpcFlow flow;            ///< flow-field crowd instead of waypoints when enabled
  NpcFormation formation;  ///< a fixed group instead of waypoints when enabled
  NpcColony colony;        ///< an ant colony instead of waypoints when enabled
  NpcRoads roads;          ///< travels a road network instead of wandering when enabled
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

/// A unit quaternion (w, x, y, z); the identity by default.
struct SceneQuat {
  double w = 1, x = 0, y = 0, z = 0;
};

/// A named rigid body placed by hand (physics.bodies), for joints and set pieces.
struct SceneBody {
  enum class Shape { Sphere, Box, Capsule };
  /// Dynamic bodies are entities; static and kinematic ones are scene geometry that every zone
  /// places itself (a kinematic body's pose is a closed form of time).
  enum class Motion { Dynamic, Static, Kinematic };
  std::string name;
  Shape shape = Shape::Sphere;
  Motion motion = Motion::Dynamic;
  SceneVec3 position;
  SceneQuat orientation;    ///< at the start
  SceneVec3 size{1, 1, 1};  ///< box: full edge lengths (m)
  double radius = 0.5;      ///< sphere and capsule (m)
  double length = 1.0;      ///< capsule: inner segment along local y (m)
  SceneVec3 velocity;
  SceneVec3 angular_velocity;
  double mass = 1.0;
  double friction = 0.5;
  double restitution = 0.0;
};

/// A joint between named bodies, or a body and the world (physics.joints; one zone only).
struct SceneJoint {
  enum class Type { Distance, Ball, Hinge };
  Type type = Type::Ball;
  int a = 0;                ///< index into PhysicsSettings::bodies
  int b = -1;               ///< index, or -1: joined to the world
  SceneVec3 anchor;         ///< ball, hinge: the world point joined at the start
  SceneVec3 anchor_a;       ///< distance: world point on a at the start (default: a's centre)
  SceneVec3 anchor_b;       ///< distance: world point on b, or in the world
  SceneVec3 axis{0, 0, 1};  ///< hinge: world axis at the start (normalised)
  double length = 0;        ///< distance: rod length (default: |anchor_b - anchor_a|)
};

/// A mass-spring cloth patch (physics.cloths; one zone only).
struct SceneCloth {
  SceneVec3 origin;                ///< particle (0, 0)
  int columns = 10, rows = 10;     ///< particles along column_axis and row_axis
  double spacing = 0.1;            ///< m between neighbours
  SceneVec3 column_axis{1, 0, 0};  ///< normalised
  SceneVec3 row_axis{0, -1, 0};    ///< normalised, not parallel to column_axis
  double particle_mass = 0.01;
  double stiffness = 200, shear_stiffness = 50, bend_stiffness = 10;  ///< N/m
  double damping = 0.05;                                              ///< N s/m along each spring
  double tear_strain = 0;                 ///< springs past this strain are removed; 0: never
  double thickness = 0.02;                ///< m kept between particles and bodies
  double friction = 0.3;                  ///< against bodies
  int substeps = 0;                       ///< per tick; 0: chosen from the stiffness
  std::vector<std::pair<int, int>> pins;  ///< (column, row) held in place
};

/// An explosion at a time and place (physics.explosions): an instant impulse or a blast.
struct SceneExplosion {
  enum class Falloff { Constant, Linear, Quadratic };
  double time = 0;  ///< s of simulated time; fires at the first tick starting at or after it
  SceneVec3 position;
  double radius = 5;
  double impulse = 0;   ///< N s at the centre (instant); 0 when it is a blast
  double force = 0;     ///< N at the centre (blast); 0 when it is an impulse
  double duration = 0;  ///< s a blast lasts
  Falloff falloff = Falloff::Linear;
};

/// The rigid-body engine's approximations (physics/).
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
  double sor_omega = 1.3;                  ///< over-relaxation factor of the sor solver
  std::vector<SceneBody> bodies;           ///< named bodies (entities after the populations)
  std::vector<SceneJoint> joints;          ///< between named bodies
  std::vector<SceneCloth> cloths;          ///< zone-local, not sent to clients
  std::vector<SceneExplosion> explosions;  ///< each zone applies them to its own bodies
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

/// Level of detail for crowds (crowd/lod.h): NPCs far from every player are updated
/// less often, the farthest without steering (`lod:` key; absent: every NPC every tick).
struct CrowdLod {
  bool enabled = false;     ///< the scene has a `lod` key
  double near_radius = 40;  ///< m from the nearest player: every tick, full steering
  double far_radius = 120;  ///< m: between near and far, every `mid_every` ticks
  int mid_every = 2;        ///< ticks between updates of the middle band
  int far_every = 8;        ///< ticks between updates beyond far_radius
  bool mid_steers = true;   ///< the middle band keeps its neighbour terms
  bool far_steers = false;  ///< the far band follows its field only
  /// Fixed ground-plane points (x, z) that count as players (scripted observers: runs
  /// without clients, tests, points of interest that keep full detail).
  std::vector<std::pair<double, double>> observers;
};

/// A whole scene; the docs for every key are in docs/scene-format.md.
struct Scene {
  std::string name;
  std::string source_path;  ///< file it was loaded from; empty from parseScene()
  SceneBox world;
  double tick_rate = 30;  ///< ticks per second of wall time when running real-time
  double dt = 1.0 / 30;   ///< simulated seconds per tick
  std::uint64_t seed = 1;
  SceneZones zones;
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
  AgentSettings agents;    ///< AI agent types and populations (common/scene_ai.h)
  CrowdLod lod;            ///< level of detail of the crowd systems
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
