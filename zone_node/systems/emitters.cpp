#include "zone_node/systems/emitters.h"

#include <cmath>

#include "common/rng.h"
#include "common/scene_emitters.h"
#include "gpu/backend.h"
#include "gpu/particle_system.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

namespace {
constexpr gpu::Vec3d kGravity{0.0, -9.81, 0.0};
/// Sprays go up in a cone of this half angle (radians).
constexpr double kConeHalfAngle = 0.6;
}  // namespace

EmitterSystem::EmitterSystem(const std::vector<EmitterPopulation>& emitters,
                             const std::string& gpu_mode,
                             const gpu::OffloadThresholds& thresholds) {
  std::size_t total = 0;
  for (const EmitterPopulation& p : emitters) {
    std::size_t budget = std::size_t(p.count) * std::size_t(p.max_particles);
    capacity_[{p.drag, p.restitution}] += budget;
    total += budget;
  }
  if (total == 0) return;
  // One decision for the zone, from the scene's whole particle budget: on for big batches only.
  opencl_ = gpu::chooseBackend(gpu::parseGpuMode(gpu_mode), gpu::Workload::Particles, total,
                               gpu::openClAvailable(), thresholds) == gpu::Backend::OpenCl;
  backend_ = gpu::backendName(opencl_ ? gpu::Backend::OpenCl : gpu::Backend::Cpu);
}

EmitterSystem::~EmitterSystem() = default;

std::string EmitterSystem::backendName() const {
  return backend_;
}

gpu::ParticleSystem& EmitterSystem::batchFor(const EmitterData& e) {
  Medium key{e.drag, e.restitution};
  auto it = batches_.find(key);
  if (it != batches_.end()) return *it->second;
  std::size_t capacity = capacity_.count(key) ? capacity_[key] : std::size_t(e.max_particles);
  auto system = std::make_unique<gpu::ParticleSystem>(
      opencl_ ? gpu::Backend::OpenCl : gpu::Backend::Cpu, capacity);
  system->reserve(capacity);
  return *batches_.emplace(key, std::move(system)).first->second;
}

void EmitterSystem::step(StepContext& ctx) {
  ctx.counters.particles_alive = advance(ctx.store, ctx.dt);
}

std::uint64_t EmitterSystem::advance(EntityStore& store, double dt) {
  if (store.count(EntityKind::Emitter) == 0 && batches_.empty()) return 0;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Emitter) continue;
    EmitterData& e = store.emitter[i];
    e.spawn_accumulator += e.rate * dt;
    auto count = std::size_t(std::floor(e.spawn_accumulator));
    if (count == 0) continue;
    e.spawn_accumulator -= double(count);
    gpu::EmitSpec spec;
    spec.origin = {store.pos[i].x(), std::max(0.0, store.pos[i].y()), store.pos[i].z()};
    spec.cone_half_angle = kConeHalfAngle;
    spec.speed = e.speed;
    spec.lifetime = e.lifetime;
    Pcg32 rng = Pcg32::fromState(store.rng_state[i], store.id[i].value);
    batchFor(e).emit(spec, count, rng);
    store.rng_state[i] = rng.state();
  }
  std::uint64_t alive = 0;
  for (auto& [medium, system] : batches_) {
    if (system->aliveCount() == 0) continue;  // nothing to integrate: no launch
    system->step(dt, kGravity, medium.first, medium.second);
    alive += system->aliveCount();
  }
  return alive;
}

void EmitterSystem::liveParticles(std::vector<std::array<double, 6>>& out) const {
  std::vector<gpu::Vec3d> pos, vel;
  for (const auto& [medium, system] : batches_) {
    system->readPositions(pos);
    system->readVelocities(vel);
    for (std::size_t i = 0; i < system->slotCount(); ++i)
      if (system->isAlive(i))
        out.push_back({pos[i].x, pos[i].y, pos[i].z, vel[i].x, vel[i].y, vel[i].z});
  }
}

}  // namespace zonesim::zone
