#include "gpu/particle_system.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gpu/cl_particles.h"
#include "gpu/cl_runtime.h"
#include "gpu/cpu_particles.h"
#include "gpu/default_runtime.h"
#include "gpu/particle_emit.h"
#include "gpu/particle_ledger.h"

namespace zonesim::gpu {
namespace {

std::unique_ptr<ParticleEngine> makeEngine(Backend backend, std::shared_ptr<ClRuntime> runtime) {
  if (backend == Backend::Cpu) return std::make_unique<CpuParticles>();
  if (!runtime) runtime = defaultRuntime();
  return std::make_unique<ClParticles>(std::move(runtime));
}

bool finite(const Vec3d& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

StepParams validateStep(double dt, const Vec3d& gravity, double drag, double restitution,
                        std::span<const Sphere> spheres) {
  StepParams params{dt, toMicros(dt, "step dt"), gravity, drag, restitution, spheres};
  for (const Sphere& s : spheres) {
    if (!finite(s.center) || !std::isfinite(s.radius) || !(s.radius > 0.0)) {
      throw std::invalid_argument("step spheres need a finite centre and a radius > 0, not " +
                                  std::to_string(s.radius));
    }
  }
  if (!finite(gravity)) {
    throw std::invalid_argument("step gravity must be finite");
  }
  // Beyond drag * dt = 1 the explicit drag term reverses velocities instead of damping them.
  if (!std::isfinite(drag) || drag < 0.0 || drag * dt > 1.0) {
    throw std::invalid_argument("step drag must be >= 0 with drag * dt <= 1, not drag " +
                                std::to_string(drag) + " at dt " + std::to_string(dt));
  }
  if (!(restitution >= 0.0 && restitution <= 1.0)) {
    throw std::invalid_argument("step restitution must be in [0, 1], not " +
                                std::to_string(restitution));
  }
  return params;
}

}  // namespace

ParticleSystem::ParticleSystem(Backend backend, std::size_t max_particles,
                               std::shared_ptr<ClRuntime> runtime)
    : backend_(backend),
      ledger_(std::make_unique<ParticleLedger>(max_particles)),
      engine_(makeEngine(backend, std::move(runtime))) {}

ParticleSystem::~ParticleSystem() = default;
ParticleSystem::ParticleSystem(ParticleSystem&&) noexcept = default;
ParticleSystem& ParticleSystem::operator=(ParticleSystem&&) noexcept = default;

std::size_t ParticleSystem::emit(const EmitSpec& spec, std::size_t count, Pcg32& rng) {
  EmitSampler sampler(spec);
  std::vector<NewParticle>& batch = batch_;
  batch.clear();
  for (std::size_t i = 0; i < count; ++i) {
    NewParticle p;
    if (!ledger_->allocate(sampler.lifeMicros(), p.slot)) break;
    p.life_us = sampler.lifeMicros();
    p.position = spec.origin;
    p.velocity = sampler.velocity(rng);
    batch.push_back(p);
  }
  engine_->upload(batch, ledger_->slotCount());
  return batch.size();
}

void ParticleSystem::step(double dt, const Vec3d& gravity, double drag, double restitution,
                          std::span<const Sphere> spheres) {
  StepParams params = validateStep(dt, gravity, drag, restitution, spheres);
  // Nothing alive: dead slots never change, so the launch would be wasted; only time moves.
  if (ledger_->aliveCount() > 0) engine_->step(params, ledger_->slotCount());
  ledger_->advance(params.dt_us);
}

void ParticleSystem::reserve(std::size_t slots) {
  slots = std::min(slots, ledger_->maxSlots());
  ledger_->reserve(slots);
  engine_->reserve(slots);
  batch_.reserve(slots);
}

std::size_t ParticleSystem::capacity() const {
  return engine_->capacity();
}

std::size_t ParticleSystem::aliveCount() const {
  return ledger_->aliveCount();
}

std::size_t ParticleSystem::slotCount() const {
  return ledger_->slotCount();
}

bool ParticleSystem::isAlive(std::size_t slot) const {
  return ledger_->alive(slot);
}

void ParticleSystem::readPositions(std::vector<Vec3d>& out) const {
  engine_->readPositions(ledger_->slotCount(), out);
}

void ParticleSystem::readVelocities(std::vector<Vec3d>& out) const {
  engine_->readVelocities(ledger_->slotCount(), out);
}

std::string ParticleSystem::deviceDescription() const {
  return engine_->description();
}

TransferStats ParticleSystem::transfers() const {
  return engine_->transfers();
}

}  // namespace zonesim::gpu
