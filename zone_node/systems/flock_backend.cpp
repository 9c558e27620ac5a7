#include "zone_node/systems/flock_backend.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/rng.h"
#include "gpu/planar_flock.h"

namespace zonesim::zone {

namespace {

void toDevice(std::span<const crowd::Vec2> in, std::vector<gpu::Vec2d>& out) {
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = {in[i].x, in[i].y};
}

gpu::PlanarFlockParams paramsOf(const crowd::FlockSettings& s) {
  gpu::PlanarFlockParams p;
  p.neighbour_radius = s.neighbour_radius;
  p.separation_radius = s.separation_radius;
  p.separation_weight = s.separation_weight;
  p.alignment_weight = s.alignment_weight;
  p.cohesion_weight = s.cohesion_weight;
  p.goal_weight = s.goal_weight;
  p.max_speed = s.max_speed;
  p.max_force = s.max_force;
  return p;
}

}  // namespace

gpu::Backend flockBackendFor(std::string_view gpu_mode, std::size_t agents,
                             const gpu::OffloadThresholds& thresholds) {
  gpu::GpuMode mode = gpu::parseGpuMode(gpu_mode);
  // Off never opens a device; on and auto ask whether one exists (on fails later without it).
  bool available = mode != gpu::GpuMode::Off && gpu::openClAvailable();
  return gpu::chooseBackend(mode, gpu::Workload::Flock, agents, available, thresholds);
}

std::vector<gpu::ProbeSample> probeFlockBackends(std::span<const std::size_t> sizes) {
  constexpr double kDensity = 0.3, kDt = 0.05;  // per m^2, as scenes/flock_large.yaml
  std::vector<gpu::ProbeSample> samples;
  for (std::size_t n : sizes) {
    // n agents in a square and their ghosts in a 3 m strip along one side.
    Pcg32 rng(19, n);
    const double side = std::sqrt(double(n) / kDensity);
    std::vector<std::uint64_t> ids(n), ghost_ids;
    std::vector<crowd::Vec2> pos(n), vel(n), ghost_pos, ghost_vel;
    for (std::size_t i = 0; i < n; ++i) {
      ids[i] = 2 * i;
      pos[i] = {rng.uniform(0, side), rng.uniform(0, side)};
      vel[i] = {rng.uniform(-2, 2), rng.uniform(-2, 2)};
    }
    for (std::size_t i = 0; i < std::size_t(side * 3 * kDensity); ++i) {
      ghost_ids.push_back(2 * i + 1);
      ghost_pos.push_back({side + rng.uniform(0, 3), rng.uniform(0, side)});
      ghost_vel.push_back({rng.uniform(-2, 2), rng.uniform(-2, 2)});
    }
    const crowd::GhostSpan ghosts{ghost_ids, ghost_pos, ghost_vel};
    auto secondsPerStep = [&](gpu::Backend backend) {
      FlockBackend flock(crowd::FlockSettings{}, backend);
      std::vector<crowd::Vec2> p = pos, v = vel;
      auto step = [&] { flock.step(crowd::AgentSpan{ids, p, v}, ghosts, kDt); };
      step();  // warm: buffers, and PoCL compiles at first launch
      double best = INFINITY;
      for (int run = 0; run < 2; ++run) {
        auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < 3; ++k) step();
        std::chrono::duration<double> s = std::chrono::steady_clock::now() - start;
        best = std::min(best, s.count() / 3);
      }
      return best;
    };
    samples.push_back({n, secondsPerStep(gpu::Backend::Cpu), secondsPerStep(gpu::Backend::OpenCl)});
  }
  return samples;
}

FlockBackend::FlockBackend(const crowd::FlockSettings& settings, gpu::Backend backend)
    : backend_(backend), cpu_(settings) {
  if (backend == gpu::Backend::OpenCl)
    device_ = std::make_unique<gpu::PlanarFlock>(paramsOf(settings));
}

FlockBackend::~FlockBackend() = default;

void FlockBackend::step(const crowd::AgentSpan& agents, const crowd::GhostSpan& ghosts, double dt,
                        std::span<const crowd::Vec2> goal_vel, const crowd::StepPlan& plan) {
  if (!device_) {
    cpu_.step(agents, ghosts, dt, goal_vel, plan);
    return;
  }
  toDevice(agents.pos, pos_);
  toDevice(agents.vel, vel_);
  toDevice(ghosts.pos, ghost_pos_);
  toDevice(ghosts.vel, ghost_vel_);
  toDevice(goal_vel, goal_);
  device_->step(agents.ids, pos_, vel_, gpu::PlanarAgents{ghosts.ids, ghost_pos_, ghost_vel_}, dt,
                gpu::PlanarControls{goal_, plan.dt, plan.steer});
  for (std::size_t i = 0; i < pos_.size(); ++i) {
    agents.pos[i] = {pos_[i].x, pos_[i].y};
    agents.vel[i] = {vel_[i].x, vel_[i].y};
  }
}

}  // namespace zonesim::zone
