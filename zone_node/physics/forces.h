#pragma once
// Force-driven accelerations: gravity, linear and quadratic drag, springs. Evaluated over whole
// arrays so that the integrators can call it at their intermediate stages.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "common/math.h"

namespace zonesim::physics {

/// Marks a spring end fixed to a world point instead of a body.
inline constexpr std::uint32_t kWorldAnchor = std::numeric_limits<std::uint32_t>::max();

/// A damped linear spring between two body centres, or a body and a fixed world point.
struct Spring {
  std::uint32_t a = 0;
  std::uint32_t b = kWorldAnchor;
  Vec3 anchor = Vec3::Zero();  ///< World point used when b is kWorldAnchor.
  double stiffness = 0.0;      ///< N/m.
  double rest_length = 0.0;    ///< m.
  double damping = 0.0;        ///< N s/m along the spring axis.
};

/// The forces acting on every body that has mass; springs act on the bodies they name.
struct ForceModel {
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);
  double linear_drag = 0.0;     ///< F = -k v (N s/m).
  double quadratic_drag = 0.0;  ///< F = -c |v| v (N s^2/m^2).
  std::vector<Spring> springs;
};

/// Writes each body's acceleration at state (x, v) plus external forces (empty span: none);
/// bodies with zero inverse mass get zero.
void evaluateAccelerations(const ForceModel& model, std::span<const Vec3> x,
                           std::span<const Vec3> v, std::span<const double> inv_mass,
                           std::span<const Vec3> external_force, std::span<Vec3> acceleration);

}  // namespace zonesim::physics
