#pragma once
// Particles for emitters (sparks, debris, smoke): gravity, linear drag, bounces on the ground
// plane y = 0 and a lifetime, integrated either by the double-precision CPU reference or on an
// OpenCL device in float. No OpenCL or Eigen header comes with it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "common/rng.h"
#include "gpu/backend.h"
#include "gpu/particle_types.h"

namespace zonesim::gpu {

class ClRuntime;
class ParticleEngine;
class ParticleLedger;
struct NewParticle;

class ParticleSystem {
 public:
  /// At most max_particles live at once. OpenCl uses runtime, else the process's default device
  /// (first GPU, else a CPU device, shared by such systems); throws NoDeviceError without one.
  explicit ParticleSystem(Backend backend, std::size_t max_particles = 1u << 20,
                          std::shared_ptr<ClRuntime> runtime = nullptr);
  ~ParticleSystem();
  ParticleSystem(ParticleSystem&&) noexcept;
  ParticleSystem& operator=(ParticleSystem&&) noexcept;

  /// Emits up to count particles, dead slots first (lowest first), then new slots; returns how
  /// many fitted under max_particles. Deterministic given rng's state; one upload per call.
  std::size_t emit(const EmitSpec& spec, std::size_t count, Pcg32& rng);
  /// Advances every live particle by dt seconds (semi-implicit Euler, see particles.cl), with
  /// bounces on the ground and on spheres. Throws std::invalid_argument unless dt is in
  /// [1 us, 4294 s], all values are finite, drag >= 0 with drag * dt <= 1, restitution is in
  /// [0, 1] and every sphere radius is > 0.
  void step(double dt, const Vec3d& gravity, double drag, double restitution,
            std::span<const Sphere> spheres = {});
  /// Sizes storage for slots particles up front, so that emits up to there allocate nothing.
  void reserve(std::size_t slots);

  /// Slots the storage (device buffers on OpenCl) holds before it has to grow.
  std::size_t capacity() const;
  /// Live particles.
  std::size_t aliveCount() const;
  /// Slots in use or once used (high-water mark); read-backs return this many entries.
  std::size_t slotCount() const;
  /// True when slot holds a live particle (dead slots keep their last state).
  bool isAlive(std::size_t slot) const;
  /// Copies the positions of every slot into out (one read-back on the OpenCL backend).
  void readPositions(std::vector<Vec3d>& out) const;
  /// Copies the velocities of every slot into out (one read-back on the OpenCL backend).
  void readVelocities(std::vector<Vec3d>& out) const;

  /// The backend chosen at construction.
  Backend backend() const { return backend_; }
  /// The device that integrates, e.g. "Portable Computing Language / pthread-... (CPU, ...)".
  std::string deviceDescription() const;
  /// Host-device traffic so far (zeros on the CPU backend).
  TransferStats transfers() const;

 private:
  Backend backend_;
  std::unique_ptr<ParticleLedger> ledger_;
  std::unique_ptr<ParticleEngine> engine_;
  // Reused across emits so that emitting allocates nothing once warmed up. NewParticle is
  // complete wherever the vector is used or destroyed (particle_system.cpp).
  std::vector<NewParticle> batch_;
};

}  // namespace zonesim::gpu
