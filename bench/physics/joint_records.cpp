// joint_records: the joint stability records at full length, with timing. Solver2D's
// ball and chain and Box2D's 100 x 100 joint grid (physics/joint_scenes.h) run 10,000 steps of
// 1/60 s under each setting; each line gives the widest joint gap seen, the gap at the end,
// the fastest body, the most the energy rose above its start, and the time per step.
//
//   joint_records [--steps N] [--grid N] [--only chain|grid]

#include <cstdio>
#include <cstring>
#include <string>

#include "bench/bench_args.h"
#include "physics/joint_scenes.h"

using namespace zonesim::physics;

namespace {

struct Setting {
  const char* name;
  int world_substeps, iterations;
  double joint_hertz;
};

// Box2D's default (4 sub-steps, 60 Hz joints), twice the sub-steps with joints twice as stiff,
// and the project's Gauss-Seidel default for comparison.
constexpr Setting kSoft[] = {{"soft 4 sub-steps, 60 Hz", 1, 8, 60.0},
                             {"soft 8 sub-steps, 120 Hz", 2, 8, 120.0}};

WorldSettings settingsOf(const Setting& s) {
  WorldSettings w;
  w.solver.kind = SolverKind::SoftStep;
  w.substeps = s.world_substeps;
  w.solver.velocity_iterations = s.iterations;
  w.solver.joint_hertz = s.joint_hertz;
  return w;
}

void report(const char* scene, const char* setting, int steps, const JointRunRecord& r) {
  std::printf("%-22s %-26s %6d %11.3e %11.3e %9.2f %12.3e %9.3f %s\n", scene, setting, steps,
              r.worst_gap, r.final_gap, r.worst_speed, r.worst_energy_gain,
              1e3 * r.seconds_per_step, r.finite ? "" : "NON-FINITE");
  std::fflush(stdout);
}

JointRunRecord runWithProgress(JointScene& scene, int steps) {
  return runJointScene(scene, steps, 10, [steps](int s, const JointRunRecord& r) {
    if (s % 1000 == 0) {
      std::fprintf(stderr, "  %d/%d steps, worst gap so far %.3e m\n", s, steps, r.worst_gap);
    }
  });
}

}  // namespace

int main(int argc, char** argv) {
  int steps = 10000, grid = 100;
  std::string only;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) {
      steps = zonesim::bench::parseCounts("--steps", argv[++i]).front();
    } else if (!std::strcmp(argv[i], "--grid") && i + 1 < argc) {
      grid = zonesim::bench::parseCounts("--grid", argv[++i]).front();
    } else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) {
      only = argv[++i];
      if (only != "chain" && only != "grid") {
        std::fprintf(stderr, "--only: '%s' is not chain or grid\n", only.c_str());
        return 2;
      }
    } else {
      std::fprintf(stderr, "usage: %s [--steps N] [--grid N] [--only chain|grid]\n", argv[0]);
      return 2;
    }
  }
  std::printf("%-22s %-26s %6s %11s %11s %9s %12s %9s\n", "scene", "solver", "steps", "worst_gap_m",
              "final_gap_m", "fastest", "energy_gain", "ms/step");
  if (only.empty() || only == "chain") {
    for (const Setting& s : kSoft) {
      BallAndChain scene(settingsOf(s));
      report("ball_and_chain", s.name, steps, runWithProgress(scene, steps));
    }
    BallAndChain scene{WorldSettings{}};
    report("ball_and_chain", "gauss-seidel 10", steps, runWithProgress(scene, steps));
  }
  if (only.empty() || only == "grid") {
    const std::string name = "joint_grid_" + std::to_string(grid);
    for (const Setting& s : kSoft) {
      JointGrid scene(settingsOf(s), grid);
      report(name.c_str(), s.name, steps, runWithProgress(scene, steps));
    }
  }
  return 0;
}
