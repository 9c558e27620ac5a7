// planar_flock_bench: one zone flock step (agents + a halo of ghosts) on the crowd library's
// double CPU flock against the OpenCL ground-plane flock (gpu/planar_flock.h), at the density
// of scenes/flock_large.yaml, with the float-versus-double velocity error of the first step.
// Usage: planar_flock_bench [N ...] (default 20000 100000); ms per step, best of 3 runs of 5.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "common/rng.h"
#include "crowd/flock.h"
#include "gpu/planar_flock.h"

namespace {

using namespace zonesim;

struct Agents {
  std::vector<std::uint64_t> ids, ghost_ids;
  std::vector<crowd::Vec2> pos, vel, ghost_pos, ghost_vel;
};

// n agents in a square at 0.3 per m^2, ghosts in a 3 m strip along two of its edges.
Agents makeAgents(std::size_t n) {
  Agents a;
  Pcg32 rng(7, 1);
  const double side = std::sqrt(double(n) / 0.3);
  for (std::size_t i = 0; i < n; ++i) {
    a.ids.push_back(2 * i);
    a.pos.push_back({rng.uniform(0, side), rng.uniform(0, side)});
    a.vel.push_back({rng.uniform(-2, 2), rng.uniform(-2, 2)});
  }
  const auto ghosts = std::size_t(2 * side * 3 * 0.3);
  for (std::size_t i = 0; i < ghosts; ++i) {
    bool east = i % 2 == 0;
    double along = rng.uniform(0, side), across = side + rng.uniform(0, 3);
    a.ghost_ids.push_back(2 * i + 1);
    a.ghost_pos.push_back(east ? crowd::Vec2{across, along} : crowd::Vec2{along, across});
    a.ghost_vel.push_back({rng.uniform(-2, 2), rng.uniform(-2, 2)});
  }
  return a;
}

template <class F>
double bestMsPerStep(F&& step) {
  double best = 1e300;
  for (int run = 0; run < 3; ++run) {
    auto t0 = std::chrono::steady_clock::now();
    for (int s = 0; s < 5; ++s) step();
    std::chrono::duration<double, std::milli> ms = std::chrono::steady_clock::now() - t0;
    best = std::min(best, ms.count() / 5);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::size_t(std::atol(argv[i])));
  if (sizes.empty()) sizes = {20000, 100000};
  constexpr double dt = 0.05;
  crowd::FlockSettings settings;
  gpu::PlanarFlockParams params;  // the same defaults as FlockSettings
  gpu::PlanarFlock device(params);
  std::printf("device: %s\n", device.deviceDescription().c_str());
  std::printf("%9s %7s %12s %12s %8s %14s\n", "agents", "ghosts", "cpu ms", "opencl ms", "cpu/cl",
              "max |dv| m/s");
  for (std::size_t n : sizes) {
    const Agents a = makeAgents(n);
    auto toDevice = [](const std::vector<crowd::Vec2>& in) {
      std::vector<gpu::Vec2d> out;
      for (crowd::Vec2 p : in) out.push_back({p.x, p.y});
      return out;
    };
    // Error of one step from the same state.
    crowd::Flock cpu(settings);
    std::vector<crowd::Vec2> pos = a.pos, vel = a.vel;
    crowd::GhostSpan ghosts{a.ghost_ids, a.ghost_pos, a.ghost_vel};
    cpu.step(crowd::AgentSpan{a.ids, pos, vel}, ghosts, dt);
    std::vector<gpu::Vec2d> dpos = toDevice(a.pos), dvel = toDevice(a.vel);
    std::vector<gpu::Vec2d> gpos = toDevice(a.ghost_pos), gvel = toDevice(a.ghost_vel);
    gpu::PlanarAgents dghosts{a.ghost_ids, gpos, gvel};
    device.step(a.ids, dpos, dvel, dghosts, dt);
    double err = 0;
    for (std::size_t i = 0; i < n; ++i)
      err = std::max(err, std::hypot(dvel[i].x - vel[i].x, dvel[i].y - vel[i].y));
    // Timing: each path keeps stepping its own state, as a zone would.
    double cpu_ms = bestMsPerStep([&] { cpu.step(crowd::AgentSpan{a.ids, pos, vel}, ghosts, dt); });
    double cl_ms = bestMsPerStep([&] { device.step(a.ids, dpos, dvel, dghosts, dt); });
    std::printf("%9zu %7zu %12.2f %12.2f %8.2f %14.2e\n", n, a.ghost_ids.size(), cpu_ms, cl_ms,
                cpu_ms / cl_ms, err);
  }
  return 0;
}
