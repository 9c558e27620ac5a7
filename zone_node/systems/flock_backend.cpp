#include "zone_node/systems/flock_backend.h"

#include "gpu/planar_flock.h"

namespace zonesim::zone {

namespace {

void toDevice(std::span<const crowd::Vec2> in, std::vector<gpu::Vec2d>& out) {
  out.resize(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) out[i] = {in[i].x, in[i].y};
}

gpu::PlanarFlockParams paramsOf(const crowd::FlockSettings& s) {
  gpu::PlanarFlockParams p;
  p.neighbour_radius = s.neighbourRadius;
  p.separation_radius = s.separationRadius;
  p.separation_weight = s.separationWeight;
  p.alignment_weight = s.alignmentWeight;
  p.cohesion_weight = s.cohesionWeight;
  p.goal_weight = s.goalWeight;
  p.max_speed = s.maxSpeed;
  p.max_force = s.maxForce;
  return p;
}

}  // namespace

gpu::Backend flockBackendFor(std::string_view gpu_mode, std::size_t population,
                             const gpu::OffloadThresholds& thresholds) {
  gpu::GpuMode mode = gpu::parseGpuMode(gpu_mode);
  // Off never opens a device; on and auto ask whether one exists (on fails later without it).
  bool available = mode != gpu::GpuMode::Off && gpu::openClAvailable();
  return gpu::chooseBackend(mode, gpu::Workload::Boids, population, available, thresholds);
}

FlockBackend::FlockBackend(const crowd::FlockSettings& settings, gpu::Backend backend)
    : backend_(backend), cpu_(settings) {
  if (backend == gpu::Backend::OpenCl)
    device_ = std::make_unique<gpu::PlanarFlock>(paramsOf(settings));
}

FlockBackend::~FlockBackend() = default;

void FlockBackend::step(const crowd::AgentSpan& agents, const crowd::GhostSpan& ghosts, double dt,
                        std::span<const crowd::Vec2> goalVel, const crowd::StepPlan& plan) {
  if (!device_) {
    cpu_.step(agents, ghosts, dt, goalVel, plan);
    return;
  }
  toDevice(agents.pos, pos_);
  toDevice(agents.vel, vel_);
  toDevice(ghosts.pos, ghost_pos_);
  toDevice(ghosts.vel, ghost_vel_);
  toDevice(goalVel, goal_);
  device_->step(agents.ids, pos_, vel_, gpu::PlanarAgents{ghosts.ids, ghost_pos_, ghost_vel_}, dt,
                gpu::PlanarControls{goal_, plan.dt, plan.steer});
  for (std::size_t i = 0; i < pos_.size(); ++i) {
    agents.pos[i] = {pos_[i].x, pos_[i].y};
    agents.vel[i] = {vel_[i].x, vel_[i].y};
  }
}

}  // namespace zonesim::zone
