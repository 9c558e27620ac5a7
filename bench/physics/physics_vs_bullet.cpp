// Runs one of issue 3's benchmark scenes on zonesim_physics and on Bullet (float; the
// physics_vs_bullet_double build links Bullet's double-precision libraries), single
// thread, dt 1/60, 10 velocity iterations (ours: plus 2 split-impulse position iterations;
// Bullet: split impulse on), sleeping off, and prints ms per step and the stability figures.
//
//   physics_vs_bullet pyramid [steps]   physics_vs_bullet spheres [steps]
//   physics_vs_bullet sleeping [steps]: zonesim only, the pyramid after it settles, with
//   sleeping on and off (the cost of a scene at rest against awake).

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <string>
#include <vector>

#include "physics/broadphase.h"
#include "physics/world.h"
#include "scenes.h"

namespace zp = zonesim::physics;
using zonesim::Vec3;

namespace {

#ifdef BT_USE_DOUBLE_PRECISION
constexpr const char* kBullet = "bullet64";  // Bullet's double-precision build.
#else
constexpr const char* kBullet = "bullet";
#endif

constexpr double kDt = 1.0 / 60.0;
constexpr double kDensity = 1000.0;

struct Timing {
  double median_ms = 0.0, mean_ms = 0.0;
};

Timing summarise(std::vector<double> ms) {
  Timing t;
  t.mean_ms = std::accumulate(ms.begin(), ms.end(), 0.0) / ms.size();
  std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
  t.median_ms = ms[ms.size() / 2];
  return t;
}

template <typename F>
double timeMs(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Vec3> runOurs(const zp::bench::Scene& scene, int steps, Timing& timing,
                          zp::SolverKind kind = zp::SolverKind::SoftStep, bool sleeping = false,
                          int settle = 0, std::size_t* asleep = nullptr) {
  zp::WorldSettings settings;
  settings.solver.kind = kind;
  settings.sleep.enabled = sleeping;
  settings.solver.velocity_iterations = 10;
  settings.solver.position_iterations = 2;
  zp::World world(settings);
  for (const auto& b : scene.bodies) {
    zp::BodyDesc d;
    d.type = b.is_static ? zp::BodyType::Static : zp::BodyType::Dynamic;
    d.shape = b.is_box ? zp::Shape::box(b.half) : zp::Shape::sphere(b.radius);
    d.position = b.position;
    d.density = kDensity;
    d.friction = scene.friction;
    d.restitution = 0.0;
    d.linear_damping = scene.damping;
    d.angular_damping = scene.damping;
    world.addBody(d);
  }
  for (int s = 0; s < settle; ++s) world.step(kDt);
  std::vector<double> ms;
  for (int s = 0; s < steps; ++s) ms.push_back(timeMs([&] { world.step(kDt); }));
  timing = summarise(ms);
  if (asleep) *asleep = world.sleepingCount();
  return world.bodies().position;
}

std::vector<Vec3> runBullet(const zp::bench::Scene& scene, int steps, Timing& timing) {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, -9.81f, 0));
  world.getSolverInfo().m_numIterations = 10;
  world.getSolverInfo().m_splitImpulse = 1;
  std::vector<btCollisionShape*> shapes;
  std::vector<btRigidBody*> bodies;
  for (const auto& b : scene.bodies) {
    btCollisionShape* shape = b.is_box ? static_cast<btCollisionShape*>(new btBoxShape(
                                             btVector3(b.half.x(), b.half.y(), b.half.z())))
                                       : new btSphereShape(b.radius);
    shapes.push_back(shape);
    const double volume = b.is_box ? 8.0 * b.half.prod() : 4.0 / 3.0 * M_PI * std::pow(b.radius, 3);
    const btScalar mass = b.is_static ? 0.0f : btScalar(kDensity * volume);
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btTransform t;
    t.setIdentity();
    t.setOrigin(btVector3(b.position.x(), b.position.y(), b.position.z()));
    auto* motion = new btDefaultMotionState(t);
    btRigidBody::btRigidBodyConstructionInfo info(mass, motion, shape, inertia);
    // Bullet multiplies the two bodies' friction: sqrt on each gives the scene's pair value.
    info.m_friction = std::sqrt(scene.friction);
    info.m_restitution = 0.0f;
    info.m_linearDamping = scene.damping;
    info.m_angularDamping = scene.damping;
    auto* body = new btRigidBody(info);
    body->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(body);
    bodies.push_back(body);
  }
  std::vector<double> ms;
  for (int s = 0; s < steps; ++s) {
    ms.push_back(timeMs([&] { world.stepSimulation(btScalar(kDt), 1, btScalar(kDt)); }));
  }
  timing = summarise(ms);
  std::vector<Vec3> out;
  for (btRigidBody* body : bodies) {
    const btVector3 p = body->getWorldTransform().getOrigin();
    out.emplace_back(p.x(), p.y(), p.z());
    world.removeRigidBody(body);
    delete body->getMotionState();
    delete body;
  }
  for (btCollisionShape* s : shapes) delete s;
  return out;
}

void reportPyramid(const char* engine, const zp::bench::Scene& scene, const std::vector<Vec3>& p,
                   const Timing& t) {
  double worst = 0.0;
  int off = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    const double d = (p[i] - scene.bodies[i].rest).norm();
    worst = std::max(worst, d);
    off += d > 0.1;
  }
  std::printf(
      "%-8s pyramid: %.2f ms/step median, %.2f mean; farthest box %.3f m from rest, "
      "%d boxes off by > 0.1 m\n",
      engine, t.median_ms, t.mean_ms, worst, off);
}

void reportSpheres(const char* engine, const zp::bench::Scene& scene, const std::vector<Vec3>& p,
                   const Timing& t) {
  std::vector<zp::Aabb> boxes;
  std::vector<std::uint8_t> moving;
  std::vector<std::size_t> index;
  double penetration = 0.0;
  int escaped = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    const double r = scene.bodies[i].radius;
    boxes.push_back(zp::Aabb{p[i] - Vec3::Constant(r), p[i] + Vec3::Constant(r)});
    moving.push_back(1);
    index.push_back(i);
    const bool inside = std::abs(p[i].x()) < 20 && std::abs(p[i].z()) < 20 && p[i].y() > 0;
    escaped += !inside;
    // Against the floor and the walls.
    penetration = std::max({penetration, r - p[i].y(), p[i].x() + r - 20, -20 - (p[i].x() - r),
                            p[i].z() + r - 20, -20 - (p[i].z() - r)});
  }
  zp::Broadphase bp(zp::BroadphaseKind::SweepAndPrune);
  std::vector<zp::ProxyPair> pairs;
  bp.findPairs(boxes, moving, pairs);
  for (const auto& pr : pairs) {
    const double d = (p[index[pr.first]] - p[index[pr.second]]).norm();
    penetration = std::max(penetration, 1.0 - d);
  }
  std::printf(
      "%-8s spheres: %.2f ms/step median, %.2f mean; largest penetration %.4f m, "
      "%d escaped\n",
      engine, t.median_ms, t.mean_ms, penetration, escaped);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string which = argc > 1 ? argv[1] : "pyramid";
  const int steps = argc > 2 ? std::atoi(argv[2]) : 500;
  if (which == "sleeping") {
    const zp::bench::Scene scene = zp::bench::pyramidScene();
    for (bool on : {false, true}) {
      Timing t;
      std::size_t asleep = 0;
      runOurs(scene, steps, t, zp::SolverKind::SoftStep, on, 300, &asleep);
      std::printf(
          "pyramid after 300 settling steps, sleeping %s: %.3f ms/step median, %.3f "
          "mean over %d steps, %zu bodies asleep\n",
          on ? "on " : "off", t.median_ms, t.mean_ms, steps, asleep);
    }
    return 0;
  }
  const bool pyramid = which == "pyramid";
  const zp::bench::Scene scene = pyramid ? zp::bench::pyramidScene() : zp::bench::spheresScene();
  std::printf("%s: %zu bodies, %d steps of 1/60 s, 10 velocity iterations\n", which.c_str(),
              scene.bodies.size(), steps);
  // Our solvers (argument 3: "soft", "pgs" or "both"), then Bullet, in the same run.
  const std::string solvers = argc > 3 ? argv[3] : "both";
  std::vector<std::pair<const char*, zp::SolverKind>> kinds;
  if (solvers != "pgs") kinds.emplace_back("zs-soft", zp::SolverKind::SoftStep);
  if (solvers != "soft") kinds.emplace_back("zs-pgs", zp::SolverKind::GaussSeidel);
  for (const auto& [name, kind] : kinds) {
    Timing t;
    const auto ours = runOurs(scene, steps, t, kind);
    if (pyramid) {
      reportPyramid(name, scene, ours, t);
    } else {
      reportSpheres(name, scene, ours, t);
    }
  }
  Timing bullet_t;
  const auto bullet = runBullet(scene, steps, bullet_t);
  if (pyramid) {
    reportPyramid(kBullet, scene, bullet, bullet_t);
  } else {
    reportSpheres(kBullet, scene, bullet, bullet_t);
  }
  return 0;
}
