// Physics level of detail in time (physics/step_lod.h), swept (issues 17 and 19): Box3D's
// many_pyramids, smaller (rows x columns pyramids of base 10 unit boxes), an observer at one
// corner, and every body farther than --near m from it stepping every k ticks. Two runs per k:
// the pyramids left standing (stability: how far the boxes drift), and a heavy ball shot into
// every pyramid (an outcome: where the debris ends). Errors are against the same run at full
// detail (k = 1); for scale, the "1 nm" row is full detail with every ball moved by 1e-9 m,
// the divergence a collapse amplifies from nothing. CSV on request for plot_physics_lod.py.
//
//   build/bin/physics_lod_sweep [--rows 8] [--columns 8] [--steps 360] [--near 40]
//                               [--max-step 0.0667] [--periods 1,2,4,8] [--csv FILE]
// Each period k runs without a longest step, and again with --max-step where k ticks exceed it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "physics/world.h"
#include "scenes.h"

namespace zp = zonesim::physics;
using zonesim::Vec3;

namespace {

constexpr double kDt = 1.0 / 60.0;

struct Options {
  int rows = 8, columns = 8, steps = 360;
  double near = 40.0;
  double max_step = 1.0 / 15.0;  // the scene default of lod.physics_max_step
  std::vector<int> periods{1, 2, 4, 8};
  std::string csv;
};

struct Run {
  std::vector<Vec3> end;     // final positions
  double ms_per_step = 0;    // mean over the run
  double body_steps = 0;     // fraction of awake body steps actually taken
};

// The pyramids' boxes, plus one ball per pyramid when `struck` (shot along +x at its base).
zp::bench::Scene sceneOf(const Options& o, bool struck, double nudge) {
  zp::bench::Scene s = zp::bench::manyPyramidsScene(o.rows, o.columns, 10);
  if (!struck) return s;
  std::vector<Vec3> lefts;  // the leftmost bottom box of each pyramid
  for (std::size_t i = 1; i < s.bodies.size(); ++i) {
    const zp::bench::SceneBody& b = s.bodies[i];
    if (std::abs(b.position.y() - 0.5) > 1e-9) continue;
    const bool leftmost = std::none_of(s.bodies.begin() + 1, s.bodies.end(), [&](const auto& o2) {
      return std::abs(o2.position.y() - 0.5) < 1e-9 && std::abs(o2.position.z() - b.position.z()) < 1e-9 &&
             o2.position.x() < b.position.x() && b.position.x() - o2.position.x() < 1.5;
    });
    if (leftmost) lefts.push_back(b.position);
  }
  for (std::size_t k = 0; k < lefts.size(); ++k) {
    zp::bench::SceneBody ball;
    ball.is_box = false;
    ball.radius = 0.5;
    ball.position = lefts[k] + Vec3(-3.0 + nudge, 1.0, 0.0);
    s.bodies.push_back(ball);
  }
  return s;
}

zp::World worldOf(const zp::bench::Scene& scene, const zp::WorldSettings& settings) {
  zp::World world(settings);
  for (const auto& b : scene.bodies) {
    zp::BodyDesc d;
    d.type = b.is_static ? zp::BodyType::Static : zp::BodyType::Dynamic;
    d.shape = b.is_box ? zp::Shape::box(b.half) : zp::Shape::sphere(b.radius);
    d.position = b.position;
    // The balls are ten times as dense as the boxes and fly at 12 m/s: each topples its pyramid.
    d.density = b.is_box ? scene.density : 10.0 * scene.density;
    d.friction = scene.friction;
    if (!b.is_box) d.linear_velocity = Vec3(12.0, 0.0, 0.0);
    world.addBody(d);
  }
  return world;
}

Run run(const zp::bench::Scene& scene, const Options& o, int period, double max_step = 0.0) {
  zp::WorldSettings settings;
  settings.lod_longest_step = max_step;
  zp::World world = worldOf(scene, settings);
  // The observer stands at the field's low corner (x, z minimal).
  const double corner = scene.bodies.front().half.x();
  const auto near = [&](const Vec3& p) {
    return std::hypot(p.x() + corner, p.z() + corner) <= o.near;
  };
  const std::size_t n = world.bodies().size();
  Run r;
  double total_ms = 0;
  for (int step = 0; step < o.steps; ++step) {
    for (std::size_t i = 1; i < n; ++i)
      world.setStepPeriod(zp::BodyIndex(i), near(world.bodies().position[i]) ? 1 : period);
    const auto t0 = std::chrono::steady_clock::now();
    world.step(kDt);
    total_ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  r.ms_per_step = total_ms / o.steps;
  const double stepped = double(world.stepLod().bodiesStepped());
  const double held = double(world.stepLod().bodiesHeld());
  r.body_steps = stepped + held > 0 ? stepped / (stepped + held) : 1.0;
  r.end = world.bodies().position;
  return r;
}

struct Errors {
  double near_max = 0, far_mean = 0, far_p99 = 0, far_max = 0;
};

Errors errorsOf(const std::vector<Vec3>& x, const std::vector<Vec3>& reference,
                const zp::bench::Scene& scene, const Options& o) {
  const double corner = scene.bodies.front().half.x();
  std::vector<double> far;
  Errors e;
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double d = (x[i] - reference[i]).norm();
    const Vec3& start = scene.bodies[i].position;
    if (std::hypot(start.x() + corner, start.z() + corner) <= o.near) {
      e.near_max = std::max(e.near_max, d);
    } else {
      far.push_back(d);
    }
  }
  if (far.empty()) return e;
  std::sort(far.begin(), far.end());
  for (double d : far) e.far_mean += d / far.size();
  e.far_p99 = far[std::min(far.size() - 1, std::size_t(0.99 * far.size()))];
  e.far_max = far.back();
  return e;
}

// The largest distance any box ended from its start (the standing pyramids' drift).
double drift(const std::vector<Vec3>& x, const zp::bench::Scene& scene) {
  double worst = 0;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (scene.bodies[i].is_box) worst = std::max(worst, (x[i] - scene.bodies[i].position).norm());
  return worst;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--rows") o.rows = zonesim::bench::parseCounts("--rows", value()).front();
    else if (a == "--columns") o.columns = zonesim::bench::parseCounts("--columns", value()).front();
    else if (a == "--steps") o.steps = zonesim::bench::parseCounts("--steps", value()).front();
    else if (a == "--near") o.near = std::atof(value());
    else if (a == "--max-step") o.max_step = std::atof(value());
    else if (a == "--periods") o.periods = zonesim::bench::parseCounts("--periods", value());
    else if (a == "--csv") o.csv = value();
    else {
      std::fprintf(stderr,
                   "unknown option %s\nusage: physics_lod_sweep [--rows N] [--columns N] "
                   "[--steps N] [--near M] [--max-step S] [--periods 1,2,4,8] [--csv FILE]\n",
                   a.c_str());
      std::exit(2);
    }
  }
  if (!(o.near >= 0.0)) {
    std::fprintf(stderr, "--near must be a distance >= 0 m\n");
    std::exit(2);
  }
  if (!(o.max_step >= 0.0)) {
    std::fprintf(stderr, "--max-step must be >= 0 s (0: no limit)\n");
    std::exit(2);
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  FILE* csv = o.csv.empty() ? nullptr : std::fopen(o.csv.c_str(), "w");
  if (!o.csv.empty() && !csv) {
    std::fprintf(stderr, "cannot write %s\n", o.csv.c_str());
    return 2;
  }
  if (csv) std::fprintf(csv, "run,period,ms_per_step,body_steps,near_max,far_mean,far_p99,far_max,drift\n");
  std::printf("many_pyramids %d x %d (base 10), %d steps at 60 Hz, observer at the low corner, "
              "near %.0f m\n\n", o.rows, o.columns, o.steps, o.near);
  std::printf("| run | period | ms/step | speed-up | body steps taken | near max err (m) | far mean "
              "/ p99 / max err (m) | worst box drift (m) |\n|---|---|---|---|---|---|---|---|\n");
  for (const bool struck : {false, true}) {
    const char* name = struck ? "struck" : "standing";
    const zp::bench::Scene scene = sceneOf(o, struck, 0.0);
    std::fprintf(stderr, "%s: full detail...\n", name);
    const Run full = run(scene, o, 1);
    std::vector<std::pair<std::string, Run>> rows;
    for (int k : o.periods) {
      if (k == 1) {
        rows.emplace_back("1", full);
        continue;
      }
      std::fprintf(stderr, "%s: period %d...\n", name, k);
      rows.emplace_back(std::to_string(k), run(scene, o, k));
    }
    // The same periods with the longest step limited (lod.physics_max_step), where it binds.
    for (int k : o.periods) {
      if (o.max_step <= 0.0 || k * kDt <= o.max_step * (1.0 + 1e-9)) continue;
      std::fprintf(stderr, "%s: period %d, steps of at most %.4f s...\n", name, k, o.max_step);
      char label[64];
      std::snprintf(label, sizeof label, "%d (max %.3g s)", k, o.max_step);
      rows.emplace_back(label, run(scene, o, k, o.max_step));
    }
    if (struck) {
      std::fprintf(stderr, "%s: full detail, every ball moved 1 nm...\n", name);
      rows.emplace_back("1 (1 nm)", run(sceneOf(o, true, 1e-9), o, 1));
    }
    for (const auto& [label, r] : rows) {
      const Errors e = errorsOf(r.end, full.end, scene, o);
      const double d = drift(r.end, scene);
      std::printf("| %s | %s | %.2f | %.2f | %.3f | %.2g | %.3g / %.3g / %.3g | %.3g |\n", name,
                  label.c_str(), r.ms_per_step, full.ms_per_step / r.ms_per_step, r.body_steps,
                  e.near_max, e.far_mean, e.far_p99, e.far_max, d);
      if (csv)
        std::fprintf(csv, "%s,%s,%.4f,%.4f,%.6g,%.6g,%.6g,%.6g,%.6g\n", name, label.c_str(),
                     r.ms_per_step, r.body_steps, e.near_max, e.far_mean, e.far_p99, e.far_max, d);
      std::fflush(stdout);
    }
  }
  // For scale: the same standing pyramids in a plain world stepped at k/60 s throughout (no
  // level of detail), the drift the engine itself gives at each step length.
  std::printf(
      "\nplain world, every body at k/60 s per step for the same simulated time:\n\n"
      "| k | steps | worst box drift (m) |\n|---|---|---|\n");
  const zp::bench::Scene standing = sceneOf(o, false, 0.0);
  for (int k : o.periods) {
    zp::World world = worldOf(standing, {});
    const int steps = o.steps / k;
    for (int step = 0; step < steps; ++step) world.step(k * kDt);
    std::printf("| %d | %d | %.3g |\n", k, steps, drift(world.bodies().position, standing));
  }
  if (csv) std::fclose(csv);
  return 0;
}
