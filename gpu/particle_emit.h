#pragma once
// Turning an EmitSpec and a seeded generator into initial particle states, identically for
// both backends (in double; the OpenCL backend rounds to float only when it uploads).

#include <cstdint>

#include "common/rng.h"
#include "gpu/particle_types.h"

namespace zonesim::gpu {

/// A particle about to be written into its slot.
struct NewParticle {
  std::uint32_t slot = 0;
  std::uint32_t life_us = 0;
  Vec3d position;
  Vec3d velocity;
};

/// Samples velocities uniformly over the spec's cone (uniform in solid angle).
class EmitSampler {
 public:
  /// Validates spec (finite, origin.y >= 0, non-zero direction, angle in [0, pi], speed >= 0,
  /// lifetime in range); throws std::invalid_argument naming the bad field.
  explicit EmitSampler(const EmitSpec& spec);

  /// The next velocity; draws exactly two uniforms from rng, so streams stay aligned.
  Vec3d velocity(Pcg32& rng) const;
  /// The validated lifetime in microseconds.
  std::uint32_t lifeMicros() const { return life_us_; }

 private:
  Vec3d axis_;
  Vec3d u_;
  Vec3d w_;
  double cos_max_;
  double speed_;
  std::uint32_t life_us_;
};

}  // namespace zonesim::gpu
