#pragma once
// The storage and integration half of a ParticleSystem, one implementation per backend. The
// interface is called once per batch or step, never per particle. Internal to gpu/.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "gpu/particle_emit.h"
#include "gpu/particle_types.h"

namespace zonesim::gpu {

/// Validated arguments of one step.
struct StepParams {
  double dt = 0;
  std::uint32_t dt_us = 0;  ///< dt in whole microseconds, for the lifetime countdown.
  Vec3d gravity;
  double drag = 0;
  double restitution = 0;
  std::span<const Sphere> spheres;  ///< Static obstacles, valid for the duration of the call.
};

class ParticleEngine {
 public:
  virtual ~ParticleEngine() = default;

  /// Makes room for slots particles so that nothing is allocated until they are exceeded.
  virtual void reserve(std::size_t slots) = 0;
  /// Writes a batch into its slots; slot_count is the new high-water mark (may grow storage).
  virtual void upload(std::span<const NewParticle> batch, std::size_t slot_count) = 0;
  /// Integrates slots [0, slot_count) by one step; dead slots stay as they are.
  virtual void step(const StepParams& params, std::size_t slot_count) = 0;
  /// Positions of slots [0, slot_count), in slot order.
  virtual void readPositions(std::size_t slot_count, std::vector<Vec3d>& out) = 0;
  /// Velocities of slots [0, slot_count), in slot order.
  virtual void readVelocities(std::size_t slot_count, std::vector<Vec3d>& out) = 0;
  /// Slots that fit without growing.
  virtual std::size_t capacity() const = 0;
  /// Which device runs the particles.
  virtual std::string description() const = 0;
  /// Host-device traffic so far.
  virtual TransferStats transfers() const = 0;
};

}  // namespace zonesim::gpu
