// physics.bodies, .joints, .cloths and .explosions (docs/scene-format.md). Joints and cloths
// need the whole scene in one zone: a joint's bodies would have to cross zone borders together
// and a cloth is simulated by the zone that holds it, so both are rejected on more zones.

#include "common/scene_loader_physics.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "common/scene.h"

namespace zonesim {
namespace {

double length(const SceneVec3& v) {
  return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
}

SceneVec3 scaled(const SceneVec3& v, double s) {
  return {v.x * s, v.y * s, v.z * s};
}

bool insideWorld(const SceneVec3& p, const SceneBox& w) {
  return p.x >= w.min.x && p.x <= w.max.x && p.y >= w.min.y && p.y <= w.max.y && p.z >= w.min.z &&
         p.z <= w.max.z;
}

SceneVec3 pointInWorld(const SceneNode& node, const SceneBox& world) {
  SceneVec3 p = node.vec3();
  if (!insideWorld(p, world)) node.fail("is outside the world");
  return p;
}

/// A unit direction from a non-zero vec3.
SceneVec3 direction(const SceneNode& node) {
  SceneVec3 v = node.vec3();
  double n = length(v);
  if (n < 1e-9) node.fail("must not be the zero vector");
  return scaled(v, 1.0 / n);
}

/// rotation: {axis: [x, y, z], degrees: a} as a unit quaternion.
SceneQuat readRotation(const SceneNode& node) {
  SceneMap m = node.map({"axis", "degrees"});
  const SceneVec3 axis = direction(m.required("axis"));
  double degrees = 0;
  m.read("degrees", degrees, Limit::between(-360, 360));
  const double half = 0.5 * degrees * M_PI / 180.0, s = std::sin(half);
  return {std::cos(half), axis.x * s, axis.y * s, axis.z * s};
}

/// The size keys of a sphere, box or capsule (a body's or a compound part's).
template <class Sized>
void readSize(SceneMap& m, Sized& b) {
  if (auto size = m.optional("size")) {
    if (b.shape != SceneBody::Shape::Box) m.failAt("size", "only boxes have a size");
    b.size = size->vec3();
    if (b.size.x <= 0 || b.size.y <= 0 || b.size.z <= 0) m.failAt("size", "every edge must be > 0");
  }
  m.read("radius", b.radius, Limit::above(0));
  m.read("length", b.length, Limit::above(0));
}

SceneBody::Part readPart(const SceneNode& node) {
  SceneMap m = node.map({"shape", "position", "rotation", "size", "radius", "length"});
  SceneBody::Part p;
  m.required("shape");
  p.shape = SceneBody::Shape(m.choice("shape", {"sphere", "box", "capsule"}, 0));
  if (auto at = m.optional("position")) p.position = at->vec3();
  if (auto r = m.optional("rotation")) p.orientation = readRotation(*r);
  readSize(m, p);
  return p;
}

SceneBody readBody(const SceneNode& node, const Scene& scene,
                   const std::vector<SceneBody>& earlier) {
  SceneMap m = node.map({"name", "motion", "shape", "position", "rotation", "size", "radius",
                         "length", "parts", "velocity", "angular_velocity", "mass", "friction",
                         "rolling_resistance", "restitution", "linear_damping", "angular_damping"});
  SceneBody b;
  SceneNode name = m.required("name");
  b.name = name.text();
  if (b.name.empty()) name.fail("must not be empty");
  for (const SceneBody& e : earlier)
    if (e.name == b.name) name.fail("another body is already called '" + b.name + "'");
  b.motion = SceneBody::Motion(m.choice("motion", {"dynamic", "static", "kinematic"}, 0));
  b.shape = SceneBody::Shape(m.choice("shape", {"sphere", "box", "capsule", "compound"}, 0));
  b.position = pointInWorld(m.required("position"), scene.world);
  if (auto r = m.optional("rotation")) b.orientation = readRotation(*r);
  if (b.shape == SceneBody::Shape::Compound) {
    for (const char* key : {"size", "radius", "length"})
      if (m.optional(key)) m.failAt(key, "a compound is sized by its parts");
    SceneNode parts = m.required("parts");
    for (const SceneNode& p : parts.items()) b.parts.push_back(readPart(p));
    if (b.parts.empty()) parts.fail("a compound needs at least one part");
    if (b.parts.size() > 256) parts.fail("at most 256 parts");
  } else {
    if (m.optional("parts")) m.failAt("parts", "only compound bodies have parts");
    readSize(m, b);
  }
  if (auto v = m.optional("velocity")) b.velocity = v->vec3();
  if (auto w = m.optional("angular_velocity")) b.angular_velocity = w->vec3();
  if (b.motion != SceneBody::Motion::Dynamic) {
    if (m.optional("mass")) m.failAt("mass", "only dynamic bodies have a mass");
    for (const char* key : {"linear_damping", "angular_damping"})
      if (m.optional(key)) m.failAt(key, "only dynamic bodies are damped");
  }
  if (b.motion == SceneBody::Motion::Static)
    for (const char* key : {"velocity", "angular_velocity"})
      if (m.optional(key)) m.failAt(key, "a static body does not move");
  m.read("mass", b.mass, Limit::above(0));
  m.read("friction", b.friction, Limit::atLeast(0));
  m.read("rolling_resistance", b.rolling_resistance, Limit::atLeast(0));
  checkRollingSolver(m, b.rolling_resistance, scene.physics);
  m.read("restitution", b.restitution, Limit::between(0, 1));
  m.read("linear_damping", b.linear_damping, Limit::atLeast(0));
  m.read("angular_damping", b.angular_damping, Limit::atLeast(0));
  return b;
}

int bodyIndex(const SceneNode& node, const std::vector<SceneBody>& bodies) {
  std::string name = node.text();
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == name) return int(i);
  node.fail("no body called '" + name + "' in physics.bodies");
}

SceneJoint readJoint(const SceneNode& node, const Scene& scene) {
  SceneMap m =
      node.map({"type", "a", "b", "anchor", "anchor_a", "anchor_b", "axis", "length", "collide"});
  const std::vector<SceneBody>& bodies = scene.physics.bodies;
  SceneJoint j;
  m.required("type");
  j.type = SceneJoint::Type(m.choice("type", {"distance", "ball", "hinge"}, 0));
  j.a = bodyIndex(m.required("a"), bodies);
  if (auto b = m.optional("b")) {
    j.b = bodyIndex(*b, bodies);
    if (j.b == j.a) b->fail("a joint needs two different bodies");
  }
  const bool a_fixed = bodies[j.a].motion != SceneBody::Motion::Dynamic;
  if (a_fixed && (j.b < 0 || bodies[j.b].motion != SceneBody::Motion::Dynamic))
    node.fail("a joint needs a dynamic body: static and kinematic bodies cannot be moved by it");
  auto only = [&](const char* key, bool allowed, const char* types) {
    if (!allowed && m.optional(key)) m.failAt(key, std::string("only ") + types + " have it");
  };
  const bool distance = j.type == SceneJoint::Type::Distance;
  only("anchor", !distance, "ball and hinge joints");
  only("anchor_a", distance, "distance joints");
  only("anchor_b", distance, "distance joints");
  only("length", distance, "distance joints");
  only("axis", j.type == SceneJoint::Type::Hinge, "hinges");
  m.read("collide", j.collide);
  if (!j.collide && j.b < 0) m.failAt("collide", "a joint to the world has no second body to skip");
  if (!distance) {
    j.anchor = pointInWorld(m.required("anchor"), scene.world);
    if (auto axis = m.optional("axis")) j.axis = direction(*axis);
    return j;
  }
  j.anchor_a = bodies[j.a].position;
  if (auto a = m.optional("anchor_a")) j.anchor_a = pointInWorld(*a, scene.world);
  if (j.b >= 0) {
    j.anchor_b = bodies[j.b].position;
    if (auto b = m.optional("anchor_b")) j.anchor_b = pointInWorld(*b, scene.world);
  } else {
    j.anchor_b = pointInWorld(m.required("anchor_b"), scene.world);
  }
  SceneVec3 d{j.anchor_b.x - j.anchor_a.x, j.anchor_b.y - j.anchor_a.y,
              j.anchor_b.z - j.anchor_a.z};
  j.length = length(d);
  m.read("length", j.length, Limit::atLeast(0));
  return j;
}

SceneCloth readCloth(const SceneNode& node, const Scene& scene) {
  SceneMap m =
      node.map({"origin", "columns", "rows", "spacing", "column_axis", "row_axis", "particle_mass",
                "stiffness", "shear_stiffness", "bend_stiffness", "damping", "tear_strain",
                "thickness", "friction", "integrator", "substeps", "pins"});
  SceneCloth c;
  c.origin = pointInWorld(m.required("origin"), scene.world);
  m.read("columns", c.columns, Limit::between(1, 256));
  m.read("rows", c.rows, Limit::between(1, 256));
  m.read("spacing", c.spacing, Limit::above(0));
  if (auto a = m.optional("column_axis")) c.column_axis = direction(*a);
  if (auto a = m.optional("row_axis")) c.row_axis = direction(*a);
  const SceneVec3 &u = c.column_axis, &v = c.row_axis;
  SceneVec3 cross{u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x};
  if (length(cross) < 1e-6) m.failAt("row_axis", "must not be parallel to column_axis");
  m.read("particle_mass", c.particle_mass, Limit::above(0));
  m.read("stiffness", c.stiffness, Limit::above(0));
  m.read("shear_stiffness", c.shear_stiffness, Limit::atLeast(0));
  m.read("bend_stiffness", c.bend_stiffness, Limit::atLeast(0));
  m.read("damping", c.damping, Limit::atLeast(0));
  m.read("tear_strain", c.tear_strain, Limit::atLeast(0));
  m.read("thickness", c.thickness, Limit::atLeast(0));
  m.read("friction", c.friction, Limit::atLeast(0));
  c.integrator = SceneCloth::Integrator(
      m.choice("integrator", {"semi_implicit_euler", "implicit_euler"}, int(c.integrator)));
  m.read("substeps", c.substeps, Limit::between(0, 10000));
  for (auto corner :
       {SceneVec3{0, 0, 0}, SceneVec3{double(c.columns - 1), double(c.rows - 1), 0}}) {
    SceneVec3 p{c.origin.x + c.spacing * (corner.x * u.x + corner.y * v.x),
                c.origin.y + c.spacing * (corner.x * u.y + corner.y * v.y),
                c.origin.z + c.spacing * (corner.x * u.z + corner.y * v.z)};
    if (!insideWorld(p, scene.world)) m.failAt("spacing", "the patch reaches outside the world");
  }
  if (auto pins = m.optional("pins")) {
    for (const SceneNode& pin : pins->items()) {
      std::vector<SceneNode> cr = pin.items();
      if (cr.size() != 2) pin.fail("expected [column, row]");
      int col = cr[0].integer(Limit::between(0, c.columns - 1));
      int row = cr[1].integer(Limit::between(0, c.rows - 1));
      c.pins.emplace_back(col, row);
    }
  }
  return c;
}

SceneExplosion readExplosion(const SceneNode& node, const Scene& scene) {
  SceneMap m = node.map({"time", "position", "radius", "impulse", "force", "duration", "falloff"});
  SceneExplosion e;
  e.time = m.required("time").number(Limit::atLeast(0));
  e.position = pointInWorld(m.required("position"), scene.world);
  e.radius = m.required("radius").number(Limit::above(0));
  e.falloff = SceneExplosion::Falloff(m.choice("falloff", {"constant", "linear", "quadratic"}, 1));
  const bool impulse = bool(m.optional("impulse")), force = bool(m.optional("force"));
  if (impulse == force) node.fail("give either impulse (instant) or force and duration (a blast)");
  if (impulse) {
    e.impulse = m.required("impulse").number(Limit::above(0));
    if (m.optional("duration")) m.failAt("duration", "only a blast (force) lasts");
  } else {
    e.force = m.required("force").number(Limit::above(0));
    e.duration = m.required("duration").number(Limit::above(0));
  }
  return e;
}

}  // namespace

void readPhysicsObjects(const SceneMap& root, Scene& scene) {
  std::optional<SceneNode> section = root.optional("physics");
  if (!section) return;
  SceneMap physics(*section);
  PhysicsSettings& ps = scene.physics;
  if (auto list = physics.optional("bodies"))
    for (const SceneNode& item : list->items())
      ps.bodies.push_back(readBody(item, scene, ps.bodies));
  if (auto list = physics.optional("joints")) {
    for (const SceneNode& item : list->items()) ps.joints.push_back(readJoint(item, scene));
  }
  if (auto list = physics.optional("cloths")) {
    for (const SceneNode& item : list->items()) ps.cloths.push_back(readCloth(item, scene));
  }
  if (auto list = physics.optional("explosions"))
    for (const SceneNode& item : list->items()) ps.explosions.push_back(readExplosion(item, scene));
}

void checkRollingSolver(const SceneMap& m, double rolling_resistance, const PhysicsSettings& ps) {
  if (rolling_resistance <= 0) return;
  if (ps.solver == PhysicsSettings::Solver::Projection)
    m.failAt("rolling_resistance", "needs a velocity solver; physics.solver projection has none");
  if (ps.solver == PhysicsSettings::Solver::SoftStepWide && ps.solver_named)
    m.failAt("rolling_resistance", "is not solved by physics.solver soft_step_wide");
}

void resolveDefaultSolver(Scene& scene) {
  PhysicsSettings& ps = scene.physics;
  if (ps.solver_named) return;
  const auto rolls = [](const auto& b) { return b.rolling_resistance > 0; };
  if (std::any_of(ps.bodies.begin(), ps.bodies.end(), rolls) ||
      std::any_of(scene.rigid_bodies.begin(), scene.rigid_bodies.end(), rolls))
    ps.solver = PhysicsSettings::Solver::SoftStep;
}

}  // namespace zonesim
