// Runs a benchmark scene on zonesim_physics and on Bullet (float; the
// physics_vs_bullet_double build links Bullet's double-precision libraries), single
// thread, dt 1/60, sleeping off, and prints ms per step, where our step went by stage, and the
// stability figures.
//
//   physics_vs_bullet pyramid [steps] [soft|pgs|wide|wide-box3d|both|all]: Jolt's pyramid, 10
//     velocity iterations (ours: plus 2 split-impulse position iterations; Bullet: split impulse
//     on); both: soft and pgs; wide-box3d: the wide soft step as Box3D sets its solver (4
//     sub-steps of one solve and one relax pass; -bf: with friction in the biased pass too, as
//     before Box2D v3.2; -ord: blocks packed in contact order, not coloured); all (the
//     default): every one of them.
//   physics_vs_bullet large_pyramid [steps] [base]: Box3D's large_pyramid (5,050 boxes at base
//     100), set as Box3D sets it: soft step with 4 sub-steps of one solve and one relax pass
//     (and the same solved wide, SoftStepWide); Bullet at 10 iterations.
//   physics_vs_bullet many_pyramids [steps] [rows]: Box3D's many_pyramids (14 x 14 pyramids of
//     base 10), the same settings.
//   physics_vs_bullet spheres [steps]: 5,000 spheres in a box.
//   physics_vs_bullet sleeping [steps]: zonesim only, the pyramid after it settles, with
//   sleeping on and off (the cost of a scene at rest against awake).
//   physics_vs_bullet creep [steps] [base]: zonesim only, how a large_pyramid of that base
//     (default 10) drifts as it stands, at every tenth of the run, per axis.
//   Each of our runs ends with a digest of every body's final state, so that two builds can be
//   shown to step a scene bitwise alike.
//   --recycle D (anywhere, pyramid and the Box3D scenes; creep: its runs recycle at D): also runs
//   each of our solvers with
//     contact recycling at distance D m (WorldSettings::contact_recycle_distance), labelled -rc,
//     and prints how many contacts a step recycled and computed.
//   --only LABEL (anywhere, the Box3D scenes and creep): runs only the solver of that label
//     (zs-wide8-rc, bullet, ...; creep: zs-soft, zs-pgs, zs-wide8), for profiling one of them.
//   --substeps N (anywhere, the Box3D scenes and creep): our soft steps take N sub-steps of one
//     solve and one relax pass instead of Box3D's 4 (stiffer contact springs: less sag).
//   --relax N (anywhere, the Box3D scenes and creep): N relax passes per sub-step instead of
//     Box3D's one (the velocities a tall stack is left with settle: less shaking and creep).

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <numeric>
#include <string>
#include <tuple>
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

// Our solver as a benchmark sets it.
struct OurSettings {
  zp::SolverKind kind = zp::SolverKind::SoftStep;
  int velocity_iterations = 10;  ///< Soft step: two per sub-step.
  int wide_lanes = 8;            ///< Wide soft step: the widest the CPU allows.
  int position_iterations = 2;   ///< Soft step: relax passes per sub-step.
  bool sleeping = false;
  int settle = 0;                        ///< Untimed steps before the timed ones.
  double recycle = 0.0;                  ///< Contact recycling distance (m); 0: off.
  bool friction_in_biased_pass = false;  ///< Wide soft step: as before Box2D v3.2.
  bool in_order = false;  ///< Wide soft step: blocks packed in contact order, not coloured.
};

// FNV-1a over the bytes of every body's position, orientation and velocities, in body order:
// equal digests mean bitwise equal states (up to hash collisions).
std::uint64_t stateDigest(const zp::BodyStorage& bodies) {
  std::uint64_t h = 1469598103934665603ULL;
  const auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ULL;
  };
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    mix(bodies.position[i].data(), 3 * sizeof(double));
    mix(bodies.orientation[i].coeffs().data(), 4 * sizeof(double));
    mix(bodies.linear_velocity[i].data(), 3 * sizeof(double));
    mix(bodies.angular_velocity[i].data(), 3 * sizeof(double));
  }
  return h;
}

/// Where our steps went, summed over the timed steps (ms).
struct Stages {
  double integrate = 0, broadphase = 0, narrowphase = 0, prepare = 0, solve = 0, islands = 0;
  void add(const zp::StepProfile& p) {
    integrate += 1e3 * p.integrate;
    broadphase += 1e3 * p.broadphase;
    narrowphase += 1e3 * p.narrowphase;
    prepare += 1e3 * p.prepare;
    solve += 1e3 * p.solve;
    islands += 1e3 * p.islands;
  }
  void print(const char* engine, int steps) const {
    const double total = integrate + broadphase + narrowphase + prepare + solve + islands;
    const auto pct = [&](double x) { return 100.0 * x / total; };
    std::printf(
        "%-8s stages, ms/step: broadphase %.2f (%.0f%%), narrowphase %.2f (%.0f%%), prepare "
        "%.2f (%.0f%%), solve+integrate positions %.2f (%.0f%%), integrate forces %.2f "
        "(%.0f%%), islands %.2f\n",
        engine, broadphase / steps, pct(broadphase), narrowphase / steps, pct(narrowphase),
        prepare / steps, pct(prepare), solve / steps, pct(solve), integrate / steps, pct(integrate),
        islands / steps);
  }
};

std::vector<Vec3> runOurs(const zp::bench::Scene& scene, int steps, Timing& timing,
                          const OurSettings& ours = {}, std::size_t* asleep = nullptr,
                          Stages* stages = nullptr,
                          const std::function<void(int, const zp::World&)>& observe = {}) {
  zp::WorldSettings settings;
  settings.solver.kind = ours.kind;
  settings.sleep.enabled = ours.sleeping;
  settings.solver.velocity_iterations = ours.velocity_iterations;
  settings.solver.position_iterations = ours.position_iterations;
  settings.solver.wide_lanes = ours.wide_lanes;
  settings.solver.friction_in_biased_pass = ours.friction_in_biased_pass;
  settings.solver.wide_in_order = ours.in_order;
  settings.contact_recycle_distance = ours.recycle;
  zp::World world(settings);
  for (const auto& b : scene.bodies) {
    zp::BodyDesc d;
    d.type = b.is_static ? zp::BodyType::Static : zp::BodyType::Dynamic;
    d.shape = b.is_box ? zp::Shape::box(b.half) : zp::Shape::sphere(b.radius);
    d.position = b.position;
    d.density = scene.density;
    d.friction = scene.friction;
    d.restitution = 0.0;
    d.linear_damping = scene.damping;
    d.angular_damping = scene.damping;
    world.addBody(d);
  }
  for (int s = 0; s < ours.settle; ++s) world.step(kDt);
  std::vector<double> ms;
  std::size_t recycled = 0, computed = 0;
  for (int s = 0; s < steps; ++s) {
    ms.push_back(timeMs([&] { world.step(kDt); }));
    if (stages) stages->add(world.profile());
    if (observe) observe(s + 1, world);
    recycled += world.recycledContacts();
    computed += world.computedContacts();
  }
  if (ours.recycle > 0.0) {
    std::printf("contacts per step: %.0f recycled, %.0f computed (recycling at %g m)\n",
                double(recycled) / steps, double(computed) / steps, ours.recycle);
  }
  std::printf("state digest %016llx\n",
              static_cast<unsigned long long>(stateDigest(world.bodies())));
  timing = summarise(ms);
  if (asleep) *asleep = world.sleepingCount();
  return world.bodies().position;
}

std::vector<Vec3> runBullet(const zp::bench::Scene& scene, int steps, Timing& timing,
                            int iterations = 10) {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
  world.setGravity(btVector3(0, -9.81f, 0));
  world.getSolverInfo().m_numIterations = iterations;
  world.getSolverInfo().m_splitImpulse = 1;
  std::vector<btCollisionShape*> shapes;
  std::vector<btRigidBody*> bodies;
  for (const auto& b : scene.bodies) {
    btCollisionShape* shape = b.is_box ? static_cast<btCollisionShape*>(new btBoxShape(
                                             btVector3(b.half.x(), b.half.y(), b.half.z())))
                                       : new btSphereShape(b.radius);
    shapes.push_back(shape);
    const double volume = b.is_box ? 8.0 * b.half.prod() : 4.0 / 3.0 * M_PI * std::pow(b.radius, 3);
    const btScalar mass = b.is_static ? 0.0f : btScalar(scene.density * volume);
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

// How far the farthest box ends from its rest place (Jolt's pyramid: its start with the gaps
// closed; Box3D's pyramids start touching, so their start), and how many end more than 1 cm
// and 0.1 m from it.
void reportHeld(const char* engine, const char* name, const zp::bench::Scene& scene,
                const std::vector<Vec3>& p, const Timing& t) {
  double worst = 0.0;
  int off_cm = 0, off_dm = 0, boxes = 0;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    if (scene.bodies[i].is_static) continue;
    const double d = (p[i] - scene.bodies[i].rest).norm();
    worst = std::max(worst, d);
    off_cm += d > 0.01;
    off_dm += d > 0.1;
    ++boxes;
  }
  std::printf(
      "%-8s %s: %.2f ms/step median, %.2f mean; farthest box %.4f m from rest, %d of %d "
      "boxes off by > 1 cm, %d by > 0.1 m\n",
      engine, name, t.median_ms, t.mean_ms, worst, off_cm, boxes, off_dm);
}

// Box3D's scenes: ours as Box3D sets its solver (soft step, 4 sub-steps of one solve and one
// relax pass), ours with Gauss-Seidel as the Jolt pyramid sets it (10 + 2 iterations), then
// Bullet at 10 iterations, in one run; the ratios of mean step times are printed last.
// The solvers of the Box3D scenes: the soft step as Box3D sets it (scalar and wide; 4
// sub-steps of one relax pass unless --substeps and --relax say otherwise) and Gauss-Seidel as
// the Jolt pyramid sets it.
struct SubStepping {
  int substeps = 4;  ///< sub-steps per 1/60 s
  int relax = 1;     ///< relax passes per sub-step
};

struct Box3dSolvers {
  OurSettings soft, pgs, wide;
  explicit Box3dSolvers(SubStepping sub = {}) {
    soft.velocity_iterations = 2 * sub.substeps;  // two per sub-step: its solve and relax
    soft.position_iterations = sub.relax;
    pgs.kind = zp::SolverKind::GaussSeidel;
    wide = soft;
    wide.kind = zp::SolverKind::SoftStepWide;
  }
};

// recycle: also each soft step with contact recycling at that distance (m; 0: not).
// only: the one run's label, or empty for all of them and the ratios.
int runBox3dScene(const char* name, const zp::bench::Scene& scene, int steps, double recycle,
                  const std::string& only, SubStepping sub) {
  std::printf(
      "%s: %zu bodies, %d steps of 1/60 s, sleeping off, soft steps at %d sub-steps of %d relax "
      "pass(es)\n",
      name, scene.bodies.size(), steps, sub.substeps, sub.relax);
  const auto [soft, pgs, wide] = Box3dSolvers(sub);
  OurSettings wide4 = wide;
  wide4.wide_lanes = 4;
  Timing soft_t, pgs_t, wide_t, wide4_t, bullet_t, soft_rc_t, wide_rc_t, wide_rc_bf_t,
      wide_rc_ord_t;
  std::vector<std::tuple<const char*, OurSettings, Timing*>> runs{{"zs-soft", soft, &soft_t},
                                                                  {"zs-pgs", pgs, &pgs_t},
                                                                  {"zs-wide8", wide, &wide_t},
                                                                  {"zs-wide4", wide4, &wide4_t}};
  if (recycle > 0.0) {
    OurSettings soft_rc = soft, wide_rc = wide;
    soft_rc.recycle = wide_rc.recycle = recycle;
    runs.emplace_back("zs-soft-rc", soft_rc, &soft_rc_t);
    runs.emplace_back("zs-wide8-rc", wide_rc, &wide_rc_t);
    // The same with friction in the biased pass too, as Box2D before v3.2.
    OurSettings wide_rc_bf = wide_rc;
    wide_rc_bf.friction_in_biased_pass = true;
    runs.emplace_back("zs-wide8-rc-bf", wide_rc_bf, &wide_rc_bf_t);
    // And with the blocks packed in contact order instead of coloured.
    OurSettings wide_rc_ord = wide_rc;
    wide_rc_ord.in_order = true;
    runs.emplace_back("zs-wide8-rc-ord", wide_rc_ord, &wide_rc_ord_t);
  }
  if (!only.empty()) {
    std::erase_if(runs, [&](const auto& run) { return std::get<0>(run) != only; });
    if (runs.empty() && only != kBullet) {
      std::fprintf(stderr, "physics_vs_bullet: --only %s: no run of that label\n", only.c_str());
      return 2;
    }
  }
  for (auto [label, settings, timing] : runs) {
    Stages stages;
    const auto p = runOurs(scene, steps, *timing, settings, nullptr, &stages);
    reportHeld(label, name, scene, p, *timing);
    stages.print(label, steps);
  }
  if (!only.empty() && only != kBullet) return 0;
  const auto q = runBullet(scene, steps, bullet_t, 10);
  reportHeld(kBullet, name, scene, q, bullet_t);
  if (!only.empty()) return 0;
  std::printf(
      "speed, Bullet mean / ours mean: soft step %.2f, Gauss-Seidel %.2f, wide soft step %.2f "
      "(8 lanes where AVX2, else 4), %.2f (4 lanes)\n",
      bullet_t.mean_ms / soft_t.mean_ms, bullet_t.mean_ms / pgs_t.mean_ms,
      bullet_t.mean_ms / wide_t.mean_ms, bullet_t.mean_ms / wide4_t.mean_ms);
  if (recycle > 0.0) {
    std::printf(
        "speed with recycling, Bullet mean / ours mean: soft step %.2f, wide soft step %.2f "
        "(friction in the biased pass too: %.2f; packed in contact order: %.2f)\n",
        bullet_t.mean_ms / soft_rc_t.mean_ms, bullet_t.mean_ms / wide_rc_t.mean_ms,
        bullet_t.mean_ms / wide_rc_bf_t.mean_ms, bullet_t.mean_ms / wide_rc_ord_t.mean_ms);
  }
  return 0;
}

// The place of body i (1 .. boxes) in a large_pyramid of that base: its level (0 at the bottom)
// and its place in the level from the left.
std::pair<int, int> pyramidPlace(std::size_t i, int base) {
  std::size_t index = i - 1;
  int level = 0;
  while (level < base && index >= static_cast<std::size_t>(base - level)) {
    index -= static_cast<std::size_t>(base - level);
    ++level;
  }
  return {level, static_cast<int>(index)};
}

// Box3D's large_pyramid at `base`, watched as it stands: at every tenth of the run, the largest
// displacement of any box along each axis and the outermost boxes of the bottom row's sideways
// move, for the soft step as Box3D sets it (scalar and wide) and Gauss-Seidel. The pyramid lies
// in the x-y plane and is symmetric in z, so motion along z is drift the solver made up.
// The farthest box along x at the end is named by level and place (the creep is at the edges).
// only: the label of one solver (zs-soft, zs-pgs, zs-wide8), or empty for all three.
int runCreep(int base, int steps, SubStepping sub, double recycle, const std::string& only) {
  auto [soft, pgs, wide] = Box3dSolvers(sub);
  soft.recycle = pgs.recycle = wide.recycle = recycle;
  const std::string sub_name = std::to_string(sub.substeps) + " sub-steps" +
                               (sub.relax > 1 ? " x " + std::to_string(sub.relax) + " relax" : "");
  const std::string soft_name = "soft step (" + sub_name + ")";
  const std::string wide_name = "wide soft step (" + sub_name + ")";
  const std::tuple<const char*, std::string, OurSettings> solvers[] = {
      {"zs-soft", soft_name, soft},
      {"zs-pgs", "Gauss-Seidel (10 + 2)", pgs},
      {"zs-wide8", wide_name, wide}};
  if (!only.empty() && std::none_of(std::begin(solvers), std::end(solvers),
                                    [&](const auto& s) { return std::get<0>(s) == only; })) {
    std::fprintf(stderr, "creep: --only %s: no solver of that label (zs-soft, zs-pgs, zs-wide8)\n",
                 only.c_str());
    return 2;
  }
  const zp::bench::Scene scene = zp::bench::largePyramidScene(base);
  std::printf("creep: large_pyramid of base %d (%zu boxes), %d steps of 1/60 s, sleeping off\n",
              base, scene.bodies.size() - 1, steps);
  std::printf(
      "| solver | step | max abs dx m | max abs dy m | max abs dz m | bottom row: left dx, "
      "right dx m | fastest box m/s | kinetic energy J |\n|---|---|---|---|---|---|---|---|\n");
  for (const auto& [label, solver_name, settings] : solvers) {
    if (!only.empty() && only != label) continue;
    const char* name = solver_name.c_str();
    const auto observe = [&](int step, const zp::World& world) {
      if (step % std::max(1, steps / 10) != 0 && step != steps) return;
      const auto& p = world.bodies().position;
      Vec3 most = Vec3::Zero();
      // A standing pyramid's boxes should not move: speed and energy are its shaking.
      double fastest = 0.0, energy = 0.0;
      for (std::size_t i = 1; i < p.size(); ++i) {
        most = most.cwiseMax((p[i] - scene.bodies[i].position).cwiseAbs());
        const Vec3& v = world.bodies().linear_velocity[i];
        fastest = std::max(fastest, v.norm());
        energy += 0.5 * v.squaredNorm() / world.bodies().inv_mass[i];
      }
      // Body 0 is the ground; the bottom row is bodies 1 .. base.
      const double left = p[1].x() - scene.bodies[1].position.x();
      const double right = p[std::size_t(base)].x() - scene.bodies[std::size_t(base)].position.x();
      std::printf("| %s | %d | %.4f | %.4f | %.4f | %.4f, %.4f | %.2e | %.2e |\n", name, step,
                  most.x(), most.y(), most.z(), left, right, fastest, energy);
    };
    Timing t;
    const auto end = runOurs(scene, steps, t, settings, nullptr, nullptr, observe);
    reportHeld(label, "large_pyramid", scene, end, t);
    const auto dx = [&](std::size_t i) { return end[i].x() - scene.bodies[i].position.x(); };
    std::size_t farthest = 1;  // the box farthest along x at the end
    for (std::size_t i = 2; i < end.size(); ++i)
      if (std::abs(dx(i)) > std::abs(dx(farthest))) farthest = i;
    const auto [level, place] = pyramidPlace(farthest, base);
    std::printf(
        "%s: farthest along x at the end: level %d (0 at the bottom), place %d of %d, dx "
        "%.4f m, dy %.4f m\n",
        name, level, place, base - level, dx(farthest),
        end[farthest].y() - scene.bodies[farthest].position.y());
  }
  return 0;
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

int main(int raw_argc, char** raw_argv) {
  // --recycle D may stand anywhere; the rest are positional.
  std::vector<char*> args;
  double recycle = 0.0;
  std::string only;
  SubStepping sub;
  for (int i = 0; i < raw_argc; ++i) {
    if (std::strcmp(raw_argv[i], "--only") == 0) {
      if (i + 1 >= raw_argc) {
        std::fprintf(stderr, "physics_vs_bullet: --only needs a run's label\n");
        return 2;
      }
      only = raw_argv[++i];
      continue;
    }
    if (std::strcmp(raw_argv[i], "--substeps") == 0 || std::strcmp(raw_argv[i], "--relax") == 0) {
      const bool relax = std::strcmp(raw_argv[i], "--relax") == 0;
      const int count = i + 1 < raw_argc ? std::atoi(raw_argv[i + 1]) : 0;
      if (count < 1 || count > 256) {
        std::fprintf(stderr, "physics_vs_bullet: %s needs a count from 1 to 256\n", raw_argv[i]);
        return 2;
      }
      (relax ? sub.relax : sub.substeps) = count;
      ++i;
      continue;
    }
    if (std::strcmp(raw_argv[i], "--recycle") == 0) {
      char* end = nullptr;
      recycle = i + 1 < raw_argc ? std::strtod(raw_argv[i + 1], &end) : 0.0;
      if (i + 1 >= raw_argc || *end != '\0' || !(recycle > 0.0) || !std::isfinite(recycle)) {
        std::fprintf(stderr, "physics_vs_bullet: --recycle needs a positive distance in m\n");
        return 2;
      }
      ++i;
      continue;
    }
    args.push_back(raw_argv[i]);
  }
  const int argc = static_cast<int>(args.size());
  char** argv = args.data();
  const std::string which = argc > 1 ? argv[1] : "pyramid";
  const bool box3d = which == "large_pyramid" || which == "many_pyramids";
  const int steps = argc > 2 ? std::atoi(argv[2]) : (box3d ? 200 : 500);
  if (which == "sleeping") {
    const zp::bench::Scene scene = zp::bench::pyramidScene();
    for (bool on : {false, true}) {
      Timing t;
      std::size_t asleep = 0;
      OurSettings ours;
      ours.sleeping = on;
      ours.settle = 300;
      runOurs(scene, steps, t, ours, &asleep);
      std::printf(
          "pyramid after 300 settling steps, sleeping %s: %.3f ms/step median, %.3f "
          "mean over %d steps, %zu bodies asleep\n",
          on ? "on " : "off", t.median_ms, t.mean_ms, steps, asleep);
    }
    return 0;
  }
  if (which == "large_pyramid") {
    const int base = argc > 3 ? std::atoi(argv[3]) : 100;
    if (base < 1 || steps < 1) {
      std::fprintf(stderr, "large_pyramid: steps and base must be positive\n");
      return 2;
    }
    return runBox3dScene("large_pyramid", zp::bench::largePyramidScene(base), steps, recycle, only,
                         sub);
  }
  if (which == "creep") {
    const int base = argc > 3 ? std::atoi(argv[3]) : 10;
    if (base < 1 || steps < 1) {
      std::fprintf(stderr, "creep: steps and base must be positive\n");
      return 2;
    }
    return runCreep(base, steps, sub, recycle, only);
  }
  if (which == "many_pyramids") {
    const int rows = argc > 3 ? std::atoi(argv[3]) : 14;
    if (rows < 1 || steps < 1) {
      std::fprintf(stderr, "many_pyramids: steps and rows must be positive\n");
      return 2;
    }
    return runBox3dScene("many_pyramids", zp::bench::manyPyramidsScene(rows, rows), steps, recycle,
                         only, sub);
  }
  if (which != "pyramid" && which != "spheres") {
    std::fprintf(stderr,
                 "physics_vs_bullet: unknown scene '%s' (pyramid, large_pyramid, many_pyramids, "
                 "spheres, sleeping, creep)\n",
                 which.c_str());
    return 2;
  }
  const bool pyramid = which == "pyramid";
  const zp::bench::Scene scene = pyramid ? zp::bench::pyramidScene() : zp::bench::spheresScene();
  std::printf("%s: %zu bodies, %d steps of 1/60 s, 10 velocity iterations\n", which.c_str(),
              scene.bodies.size(), steps);
  // Our solvers (argument 3: "soft", "pgs" or "both"), then Bullet, in the same run.
  const std::string solvers = argc > 3 ? argv[3] : "all";
  const bool all = solvers == "all", both = solvers == "both";
  const auto solverSettings = [](zp::SolverKind kind) {
    OurSettings s;
    s.kind = kind;
    return s;
  };
  std::vector<std::pair<const char*, OurSettings>> kinds;
  if (all || both || solvers == "soft") {
    kinds.emplace_back("zs-soft", solverSettings(zp::SolverKind::SoftStep));
  }
  if (all || both || solvers == "pgs") {
    kinds.emplace_back("zs-pgs", solverSettings(zp::SolverKind::GaussSeidel));
  }
  if (all || solvers == "wide") {
    kinds.emplace_back("zs-wide", solverSettings(zp::SolverKind::SoftStepWide));
  }
  if (all || solvers == "wide-box3d") {
    // The wide soft step as Box3D sets its own solver (4 sub-steps of one solve and one relax
    // pass, as on Box3D's scenes) instead of spending Jolt's 10 + 2 iterations.
    kinds.emplace_back("zs-wide-box3d", Box3dSolvers().wide);
    // And with friction in the biased pass too, as Box2D before v3.2.
    OurSettings biased_friction = Box3dSolvers().wide;
    biased_friction.friction_in_biased_pass = true;
    kinds.emplace_back("zs-wide-box3d-bf", biased_friction);
    // And with the blocks packed in contact order instead of coloured.
    OurSettings in_order = Box3dSolvers().wide;
    in_order.in_order = true;
    kinds.emplace_back("zs-wide-box3d-ord", in_order);
  }
  std::vector<std::tuple<std::string, OurSettings>> runs;
  for (const auto& [name, settings] : kinds) {
    runs.emplace_back(name, settings);
    if (recycle > 0.0) {
      OurSettings recycled = settings;
      recycled.recycle = recycle;
      runs.emplace_back(std::string(name) + "-rc", recycled);
    }
  }
  std::vector<double> means;  // ms per step, one per run
  for (const auto& [label, settings] : runs) {
    const char* name = label.c_str();
    Timing t;
    Stages stages;
    const auto ours = runOurs(scene, steps, t, settings, nullptr, &stages);
    stages.print(name, steps);
    if (pyramid) {
      reportHeld(name, "pyramid", scene, ours, t);
    } else {
      reportSpheres(name, scene, ours, t);
    }
    means.push_back(t.mean_ms);
  }
  Timing bullet_t;
  const auto bullet = runBullet(scene, steps, bullet_t);
  if (pyramid) {
    reportHeld(kBullet, "pyramid", scene, bullet, bullet_t);
  } else {
    reportSpheres(kBullet, scene, bullet, bullet_t);
  }
  std::printf("speed, Bullet mean / ours mean:");
  for (std::size_t r = 0; r < runs.size(); ++r) {
    std::printf(" %s %.2f", std::get<0>(runs[r]).c_str(), bullet_t.mean_ms / means[r]);
  }
  std::printf("\n");
  return 0;
}
