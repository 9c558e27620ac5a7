// The scene file format (docs/scene-format.md) mapped onto Scene. Each section has one reader
// that names its allowed keys, its required fields and each value's limits; SceneNode turns
// any violation into "file:line: field: what is wrong".

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ios>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "common/scene.h"
#include "common/scene_loader_adaptation.h"
#include "common/scene_loader_crowd.h"
#include "common/scene_loader_document.h"
#include "common/scene_loader_interactions.h"
#include "common/scene_loader_node.h"
#include "common/scene_loader_overlay.h"
#include "common/scene_loader_physics.h"
#include "common/scene_loader_time_dilation.h"

namespace zonesim {

void readAgents(const SceneMap& root, Scene& scene);          // common/scene_loader_agents.cpp
void readPlayerKinds(const SceneMap& clients, Scene& scene);  // common/scene_loader_kinds.cpp

namespace {

// Entity ids give the creating rank 16 bits, so a grid may have at most 2^16 zone ranks.
constexpr int kMaxZonesPerAxis = 256;
// Every interest cell is a DDS partition; far more than this is a unit mistake.
constexpr double kMaxInterestCells = 65536;

constexpr std::array<std::pair<const char*, double SceneVec3::*>, 3> kAxes{
    {{"x", &SceneVec3::x}, {"y", &SceneVec3::y}, {"z", &SceneVec3::z}}};

SceneBox readWorld(const SceneMap& root) {
  SceneMap world = root.required("world").map({"min", "max"});
  SceneNode max_node = world.required("max");
  SceneBox box{world.required("min").vec3(), max_node.vec3()};
  for (auto [axis, member] : kAxes) {
    if (box.max.*member <= box.min.*member) {
      max_node.fail(std::string("must be greater than world.min on every axis; ") + axis + " " +
                    formatNumber(box.max.*member) + " <= " + formatNumber(box.min.*member));
    }
  }
  return box;
}

void checkInside(const SceneNode& node, const SceneVec3& point, const SceneBox& world) {
  for (auto [axis, member] : kAxes) {
    double v = point.*member, lo = world.min.*member, hi = world.max.*member;
    if (v < lo || v > hi) {
      node.fail(std::string(axis) + " " + formatNumber(v) + " is outside the world [" +
                formatNumber(lo) + ", " + formatNumber(hi) + "]");
    }
  }
}

// Where a population starts; the whole world unless narrowed.
SceneBox readRegion(const SceneMap& population, const SceneBox& world) {
  std::optional<SceneNode> node = population.optional("region");
  if (!node) return world;
  SceneMap region = node->map({"min", "max"});
  SceneNode min_node = region.required("min"), max_node = region.required("max");
  SceneBox box{min_node.vec3(), max_node.vec3()};
  checkInside(min_node, box.min, world);
  checkInside(max_node, box.max, world);
  for (auto [axis, member] : kAxes) {
    if (box.max.*member < box.min.*member) {
      max_node.fail(std::string(axis) + " " + formatNumber(box.max.*member) +
                    " is below region.min " + formatNumber(box.min.*member));
    }
  }
  return box;
}

// Flocking NPCs steer by their neighbours instead of waypoints (docs/crowd.md).
void readFlock(const SceneMap& population, const Scene& scene, NpcPopulation& p) {
  if (!population.optional("flock")) return;
  if (population.optional("separation")) {
    population.failAt("separation", "a flocking population separates through flock.separation");
  }
  if (population.optional("gather")) {
    population.failAt("gather", "a flocking population follows its flock, not waypoints");
  }
  NpcFlock& f = p.flock;
  f.enabled = true;
  SceneMap m = population.section("flock", {"radius", "separation", "alignment", "cohesion",
                                            "max_speed", "max_force", "goal", "body_radius"});
  m.read("radius", f.radius, Limit::above(0));
  m.read("alignment", f.alignment_weight, Limit::atLeast(0));
  m.read("cohesion", f.cohesion_weight, Limit::atLeast(0));
  m.read("max_speed", f.max_speed, Limit::above(0));
  m.read("max_force", f.max_force, Limit::above(0));
  readFlockGoal(m, scene, f);
  SceneMap sep = m.section("separation", {"radius", "weight"});
  sep.read("radius", f.separation_radius, Limit::atLeast(0));
  sep.read("weight", f.separation_weight, Limit::atLeast(0));
  readBodyRadius(m, scene, f.body_radius);
  // Flockers across a border are seen through the halo; it must reach as far as they look.
  if (f.radius > scene.halo_width) {
    m.failAt("radius", formatNumber(f.radius) + " m is wider than halo.width (" +
                           formatNumber(scene.halo_width) + " m)");
  }
  if (f.separation_radius > f.radius) {
    sep.failAt("radius", formatNumber(f.separation_radius) +
                             " m is wider than flock.radius: neighbours beyond it are not seen");
  }
}

void readNpcs(const SceneNode& node, Scene& scene) {
  SceneMap m =
      node.map({"kind", "count", "speed", "acceleration", "waypoint_radius", "arrive_distance",
                "region", "separation", "gather", "flock", "flow", "formation", "colony", "roads"});
  NpcPopulation p;
  p.count = m.required("count").integer(Limit::atLeast(0));
  m.read("speed", p.min_speed, p.max_speed, Limit::atLeast(0));
  m.read("acceleration", p.acceleration, Limit::above(0));
  m.read("waypoint_radius", p.waypoint_radius, Limit::above(0));
  m.read("arrive_distance", p.arrive_distance, Limit::above(0));
  p.region = readRegion(m, scene.world);
  // Walkers across a border are seen through the halo; it must reach as far as they look.
  readSeparation(m, scene, p.separation_radius, p.separation_weight);
  SceneMap gather = m.section("gather", {"point", "radius", "start_s", "end_s"});
  if (std::optional<SceneNode> point = gather.optional("point")) {
    SceneVec3 at = point->vec3();  // [x, y, z] like every point in a scene; y is ignored
    p.gather.x = at.x;
    p.gather.z = at.z;
    if (p.gather.x < scene.world.min.x || p.gather.x > scene.world.max.x ||
        p.gather.z < scene.world.min.z || p.gather.z > scene.world.max.z)
      point->fail("is outside the world");
    p.gather.radius = 10;
    gather.read("radius", p.gather.radius, Limit::above(0));
    gather.read("start_s", p.gather.start_s, Limit::atLeast(0));
    p.gather.end_s = p.gather.start_s + 60;
    gather.read("end_s", p.gather.end_s, Limit::atLeast(p.gather.start_s));
  }
  readFlock(m, scene, p);
  readNpcFlow(m, scene, p);
  readNpcFormation(m, scene, p);
  readNpcColony(m, scene, p);
  readNpcRoads(m, scene, p);
  scene.npcs.push_back(p);
}

}  // namespace

double boundingRadius(const RigidBodyPopulation& p) {
  switch (p.shape) {
    case RigidBodyPopulation::Shape::Box:
      return 0.5 * std::sqrt(p.size.x * p.size.x + p.size.y * p.size.y + p.size.z * p.size.z);
    case RigidBodyPopulation::Shape::Capsule:
      return p.radius + 0.5 * p.length;
    case RigidBodyPopulation::Shape::Sphere:
      break;
  }
  return p.radius;
}

namespace {

void readRigidBodies(const SceneNode& node, Scene& scene) {
  SceneMap m = node.map({"kind", "count", "shape", "radius", "size", "length", "mass", "friction",
                         "rolling_resistance", "restitution", "linear_damping", "angular_damping",
                         "drop_height", "region"});
  RigidBodyPopulation p;
  p.count = m.required("count").integer(Limit::atLeast(0));
  p.shape = RigidBodyPopulation::Shape(m.choice("shape", {"sphere", "box", "capsule"}, 0));
  m.read("radius", p.radius, Limit::above(0));
  if (auto size = m.optional("size")) {
    if (p.shape != RigidBodyPopulation::Shape::Box) m.failAt("size", "only boxes have a size");
    p.size = size->vec3();
    if (p.size.x <= 0 || p.size.y <= 0 || p.size.z <= 0) m.failAt("size", "every edge must be > 0");
  }
  m.read("length", p.length, Limit::above(0));
  m.read("friction", p.friction, Limit::atLeast(0));
  m.read("rolling_resistance", p.rolling_resistance, Limit::atLeast(0));
  checkRollingSolver(m, p.rolling_resistance, scene.physics);
  m.read("mass", p.mass, Limit::above(0));
  m.read("restitution", p.restitution, Limit::between(0, 1));
  m.read("linear_damping", p.linear_damping, Limit::atLeast(0));
  m.read("angular_damping", p.angular_damping, Limit::atLeast(0));
  m.read("drop_height", p.drop_height, p.max_drop_height, Limit::atLeast(0));
  p.region = readRegion(m, scene.world);
  // drop_height is the gap under the body's bounding sphere, so its top starts 2 radii higher.
  double room = scene.world.max.y - scene.world.min.y;
  double bounding = boundingRadius(p);
  if (p.max_drop_height + 2 * bounding > room) {
    m.failAt("drop_height", "bodies of radius " + formatNumber(bounding) + " dropped from " +
                                formatNumber(p.max_drop_height) + " m stick out of the world (" +
                                formatNumber(room) + " m high)");
  }
  scene.rigid_bodies.push_back(p);
}

void readEmitters(const SceneNode& node, Scene& scene) {
  SceneMap m = node.map({"kind", "count", "rate", "lifetime", "speed", "restitution", "drag",
                         "max_particles", "region"});
  EmitterPopulation p;
  p.count = m.required("count").integer(Limit::atLeast(0));
  m.read("rate", p.rate, Limit::atLeast(0));
  m.read("lifetime", p.lifetime, Limit::above(0));
  m.read("speed", p.speed, Limit::atLeast(0));
  m.read("restitution", p.restitution, Limit::between(0, 1));
  m.read("drag", p.drag, Limit::atLeast(0));
  m.read("max_particles", p.max_particles, Limit::atLeast(1));
  p.region = readRegion(m, scene.world);
  scene.emitters.push_back(p);
}

struct PopulationKind {
  std::string_view name;
  void (*read)(const SceneNode&, Scene&);
};

constexpr std::array<PopulationKind, 3> kPopulationKinds{{
    {"npc", readNpcs},
    {"rigid_body", readRigidBodies},
    {"particle_emitter", readEmitters},
}};

void readPopulations(const SceneMap& root, Scene& scene) {
  std::optional<SceneNode> list = root.optional("populations");
  if (!list) return;
  for (const SceneNode& item : list->items()) {
    std::optional<SceneNode> kind = item.peek("kind");
    if (!kind) item.failChild("kind", "required field is missing");
    std::string name = kind->text();
    auto found = std::find_if(kPopulationKinds.begin(), kPopulationKinds.end(),
                              [&](const PopulationKind& k) { return k.name == name; });
    if (found == kPopulationKinds.end()) {
      kind->fail("unknown kind '" + name + "' (allowed: npc, rigid_body, particle_emitter)");
    }
    found->read(item, scene);
  }
}

void readZones(const SceneMap& root, Scene& scene) {
  SceneMap zones = root.required("zones").map({"layout", "columns", "rows"});
  scene.zones.kind = SceneZones::Kind::Grid;
  if (std::optional<SceneNode> layout = zones.optional("layout")) {
    std::string name = layout->text();
    if (name == "rcb")
      scene.zones.kind = SceneZones::Kind::Rcb;
    else if (name != "grid")
      layout->fail("unknown layout '" + name + "' (allowed: grid, rcb)");
  }
  scene.zones.columns = zones.required("columns").integer(Limit::between(1, kMaxZonesPerAxis));
  scene.zones.rows = zones.required("rows").integer(Limit::between(1, kMaxZonesPerAxis));
}

void readInterest(const SceneMap& root, Scene& scene) {
  SceneMap interest = root.section(
      "interest", {"cell_size", "keyframe_every", "aura", "nimbus_per_speed", "max_nimbus"});
  interest.read("cell_size", scene.interest_cell_size, Limit::above(0));
  interest.read("keyframe_every", scene.keyframe_every, Limit::atLeast(1));
  AuraNimbus& an = scene.aura_nimbus;
  SceneMap aura =
      interest.section("aura", {"npc", "avatar", "rigid_body", "particle_emitter", "item"});
  aura.read("npc", an.npc, Limit::above(0));
  aura.read("avatar", an.avatar, Limit::above(0));
  aura.read("rigid_body", an.rigid_body, Limit::above(0));
  aura.read("particle_emitter", an.emitter, Limit::above(0));
  aura.read("item", an.item, Limit::above(0));
  interest.read("nimbus_per_speed", an.nimbus_per_speed, Limit::atLeast(0));
  interest.read("max_nimbus", an.max_nimbus, Limit::above(0));
  double size = scene.interest_cell_size;
  double cells = std::ceil((scene.world.max.x - scene.world.min.x) / size) *
                 std::ceil((scene.world.max.z - scene.world.min.z) / size);
  if (cells > kMaxInterestCells) {
    interest.failAt("cell_size", "gives " + formatNumber(cells) + " cells, more than " +
                                     formatNumber(kMaxInterestCells) +
                                     " (each cell is a DDS partition)");
  }
}

// The offload mode is a scene setting too, so that a tuned overlay can choose it.
void readGpu(const SceneMap& root, Scene& scene) {
  static constexpr std::string_view kModes[] = {"off", "on", "auto", "probe"};
  SceneMap gpu = root.section("gpu", {"mode"});
  scene.gpu_mode = std::string(kModes[gpu.choice("mode", {"off", "on", "auto", "probe"}, 2)]);
}

// Ghosts come only from neighbouring zones, so the halo may not reach past one zone.
void readHalo(const SceneMap& root, Scene& scene) {
  SceneMap halo = root.section("halo", {"width", "skin"});
  halo.read("width", scene.halo_width, Limit::atLeast(0));
  if (halo.optional("skin")) {
    double skin = 0;
    halo.read("skin", skin, Limit::atLeast(0));
    scene.halo_skin = skin;
  }
  double zone_x = (scene.world.max.x - scene.world.min.x) / scene.zones.columns;
  double zone_z = (scene.world.max.z - scene.world.min.z) / scene.zones.rows;
  if ((scene.zones.columns > 1 && scene.halo_width > zone_x) ||
      (scene.zones.rows > 1 && scene.halo_width > zone_z)) {
    halo.failAt("width", formatNumber(scene.halo_width) + " m is wider than a zone (" +
                             formatNumber(zone_x) + " m x " + formatNumber(zone_z) + " m)");
  }
}

void readTick(const SceneMap& root, Scene& scene) {
  SceneMap tick = root.required("tick").map({"rate_hz", "dt"});
  scene.dt = tick.required("dt").number(Limit::above(0));
  scene.tick_rate = 1.0 / scene.dt;  // real time unless told otherwise
  tick.read("rate_hz", scene.tick_rate, Limit::above(0));
}

void readPhysics(const SceneMap& root, PhysicsSettings& ps) {
  SceneMap m = root.section(
      "physics", {"integrator", "broadphase", "substeps", "velocity_iterations",
                  "position_iterations", "sleep", "gyroscopic", "solver", "sor_omega",
                  "joint_hertz", "joint_damping_ratio", "linear_drag", "quadratic_drag",
                  "contact_recycle_distance", "bodies", "joints", "cloths", "explosions"});
  ps.integrator = PhysicsSettings::Integrator(
      m.choice("integrator",
               {"explicit_euler", "semi_implicit_euler", "position_verlet", "velocity_verlet",
                "rk2_midpoint", "rk4"},
               int(ps.integrator)));
  ps.broadphase = PhysicsSettings::Broadphase(
      m.choice("broadphase", {"brute_force", "sweep_and_prune", "uniform_grid", "aabb_tree"},
               int(ps.broadphase)));
  m.read("substeps", ps.substeps, Limit::between(1, 64));
  m.read("velocity_iterations", ps.velocity_iterations, Limit::between(1, 1000));
  m.read("position_iterations", ps.position_iterations, Limit::between(0, 1000));
  m.read("sleep", ps.sleep);
  m.read("gyroscopic", ps.gyroscopic);
  ps.solver_named = m.optional("solver").has_value();
  ps.solver =
      PhysicsSettings::Solver(m.choice("solver",
                                       {"soft_step", "gauss_seidel", "sor", "jacobi", "penalty",
                                        "projection", "conjugate_gradient", "soft_step_wide"},
                                       int(ps.solver)));
  m.read("sor_omega", ps.sor_omega, Limit::between(0.1, 1.99));
  m.read("joint_hertz", ps.joint_hertz, Limit::between(0.1, 1e4));
  m.read("joint_damping_ratio", ps.joint_damping_ratio, Limit::between(0, 100));
  m.read("linear_drag", ps.linear_drag, Limit::atLeast(0));
  m.read("quadratic_drag", ps.quadratic_drag, Limit::atLeast(0));
  m.read("contact_recycle_distance", ps.contact_recycle_distance, Limit::between(0, 1));
}

void readDeadReckoningModel(const SceneMap& models, std::string_view kind,
                            DeadReckoningModel& model) {
  SceneMap m = models.section(kind, {"order", "orientation"});
  model.order =
      DeadReckoningModel::Order(m.choice("order", {"static", "first", "second"}, int(model.order)));
  model.rotating = m.choice("orientation", {"fixed", "rotating"}, model.rotating ? 1 : 0) == 1;
}

void readQuantisation(const SceneMap& dr_map, StateQuantisation& q) {
  SceneMap m = dr_map.section(
      "quantisation", {"position_resolution", "max_speed", "velocity_resolution",
                       "max_acceleration", "acceleration_resolution", "max_angular_velocity",
                       "angular_velocity_resolution", "rotation_bits"});
  // Bounded so every field fits in well under 32 bits.
  m.read("position_resolution", q.position_resolution, Limit::between(1e-4, 1));
  m.read("max_speed", q.max_speed, Limit::between(1, 1e4));
  m.read("velocity_resolution", q.velocity_resolution, Limit::between(1e-4, 1));
  m.read("max_acceleration", q.max_acceleration, Limit::between(1, 1e4));
  m.read("acceleration_resolution", q.acceleration_resolution, Limit::between(1e-4, 1));
  m.read("max_angular_velocity", q.max_angular_velocity, Limit::between(1, 1e3));
  m.read("angular_velocity_resolution", q.angular_velocity_resolution, Limit::between(1e-4, 1));
  m.read("rotation_bits", q.rotation_bits, Limit::between(4, 16));
}

void readDeadReckoning(const SceneMap& root, DeadReckoning& dr) {
  SceneMap m = root.section(
      "dead_reckoning",
      {"position_threshold", "heartbeat_s", "orientation_threshold_deg", "models", "quantisation"});
  m.read("position_threshold", dr.position_threshold, Limit::atLeast(0));
  m.read("heartbeat_s", dr.heartbeat_seconds, Limit::above(0));
  m.read("orientation_threshold_deg", dr.orientation_threshold_deg, Limit::between(0, 180));
  SceneMap models = m.section("models", {"npc", "avatar", "rigid_body", "particle_emitter"});
  readDeadReckoningModel(models, "npc", dr.npc);
  readDeadReckoningModel(models, "avatar", dr.avatar);
  readDeadReckoningModel(models, "rigid_body", dr.rigid_body);
  readDeadReckoningModel(models, "particle_emitter", dr.emitter);
  readQuantisation(m, dr.quantisation);
}

void readClients(const SceneMap& root, Scene& scene) {
  ClientProfile& clients = scene.clients;
  SceneMap m = root.section("clients", {"players", "speed", "input_hz", "nimbus", "retarget_s",
                                        "downlink_kbps", "downlink_error_angle_deg", "kinds"});
  m.read("players", clients.players, Limit::atLeast(0));
  m.read("speed", clients.speed, Limit::atLeast(0));
  m.read("input_hz", clients.input_hz, Limit::above(0));
  m.read("nimbus", clients.nimbus, Limit::above(0));
  m.read("retarget_s", clients.retarget_seconds, Limit::above(0));
  m.read("downlink_kbps", clients.downlink_kbps, Limit::atLeast(0));
  m.read("downlink_error_angle_deg", clients.downlink_error_angle_deg, Limit::between(0, 85));
  readPlayerKinds(m, scene);  // after speed and nimbus: a kind's defaults
}

Scene readScene(const SceneNode& document, const std::string& file) {
  SceneMap root =
      document.map({"name", "world", "tick", "seed", "zones", "interest", "halo", "dead_reckoning",
                    "physics", "populations", "clients", "map", "agents", "lod", "time_dilation",
                    "interactions", "adaptation", "gpu"});
  Scene scene;
  scene.name = std::filesystem::path(file).stem().string();
  if (std::optional<SceneNode> name = root.optional("name")) {
    scene.name = name->text();
    if (scene.name.empty()) name->fail("must not be empty");
  }
  scene.world = readWorld(root);
  readTick(root, scene);
  scene.seed = root.required("seed").unsignedInteger();
  readZones(root, scene);
  readInterest(root, scene);
  readHalo(root, scene);
  readDeadReckoning(root, scene.dead_reckoning);
  readPhysics(root, scene.physics);
  readPhysicsObjects(root, scene);  // common/scene_loader_physics.cpp
  readObstacleMap(root, scene);
  readPopulations(root, scene);
  readClients(root, scene);
  readAgents(root, scene);
  readCrowdLod(root, scene);
  readTimeDilation(root, scene.time_dilation);
  readInteractions(root, scene.world, scene.halo_width, scene.interactions);
  readAdaptation(root, scene.world, scene.adaptation);
  readGpu(root, scene);
  resolveDefaultSolver(scene);
  return scene;
}

// Nothing for a path that cannot be read, a directory included (libstdc++ throws on its read).
std::optional<std::string> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  try {
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::ios_base::failure&) {
    return std::nullopt;
  }
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& name) {
  SceneOrigins origins;
  YAML::Node document = parseSceneWithOverlays(text, name, origins);
  // An overlay is its base scene with changes: the base names it and anchors its paths.
  return readScene(SceneNode::root(document, origins), origins.root_file);
}

Scene loadScene(const std::string& path) {
  std::optional<std::string> text = readFile(path);
  if (!text) throwSceneError(path, 0, "file", "cannot open");
  Scene scene = parseScene(*text, path);
  scene.source_path = path;
  return scene;
}

}  // namespace zonesim
