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

/// How an explosion weakens with distance r from its centre, out to its radius R.
enum class Falloff {
  Constant,   ///< Full strength anywhere inside R.
  Linear,     ///< 1 - r/R.
  Quadratic,  ///< (1 - r/R)^2.
};

/// Strength factor of a falloff at distance r (0 outside the radius).
double falloffFactor(Falloff falloff, double r, double radius);

/// A blast: a radial force on every body's centre of mass inside the radius, for a duration
/// (World::step counts it down and removes it). Pushes away from the centre; no torque.
struct Blast {
  Vec3 centre = Vec3::Zero();
  double force = 0.0;   ///< N at the centre (before falloff).
  double radius = 1.0;  ///< m.
  Falloff falloff = Falloff::Linear;
  double remaining = 0.0;  ///< s of force left.
};

/// The forces acting on every body that has mass; springs act on the bodies they name.
struct ForceModel {
  Vec3 gravity = Vec3(0.0, -9.81, 0.0);
  double linear_drag = 0.0;     ///< F = -k v (N s/m).
  double quadratic_drag = 0.0;  ///< F = -c |v| v (N s^2/m^2).
  std::vector<Spring> springs;
  std::vector<Blast> blasts;
};

/// Writes each body's acceleration at state (x, v) plus external forces (empty span: none);
/// bodies with zero inverse mass get zero.
void evaluateAccelerations(const ForceModel& model, std::span<const Vec3> x,
                           std::span<const Vec3> v, std::span<const double> inv_mass,
                           std::span<const Vec3> external_force, std::span<Vec3> acceleration);

}  // namespace zonesim::physics
