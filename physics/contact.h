#pragma once
// Contact manifolds: what the narrowphase produces and the solver consumes.

#include <array>
#include <cstdint>

#include "common/math.h"

namespace zonesim::physics {

/// One contact point. depth > 0 is penetration, depth < 0 a speculative gap.
struct ContactPoint {
  Vec3 position = Vec3::Zero();  ///< Midway between the two surfaces.
  double depth = 0.0;
  std::uint32_t feature = 0;  ///< Identifies the point across steps for warm starting.
};

/// Up to four points sharing one normal, which points from shape A towards shape B.
struct Manifold {
  Vec3 normal = Vec3::UnitY();
  std::array<ContactPoint, 4> points{};
  int count = 0;

  /// Appends a point if there is room.
  void add(const Vec3& position, double depth, std::uint32_t feature) {
    if (count < 4) points[count++] = ContactPoint{position, depth, feature};
  }
};

/// A shape's placement in the world.
struct Pose {
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

}  // namespace zonesim::physics
