#include "physics/forces.h"

namespace zonesim::physics {

double falloffFactor(Falloff falloff, double r, double radius) {
  if (r >= radius) return 0.0;
  const double t = 1.0 - r / radius;
  switch (falloff) {
    case Falloff::Constant:
      return 1.0;
    case Falloff::Linear:
      return t;
    case Falloff::Quadratic:
      return t * t;
  }
  return 0.0;
}

void evaluateAccelerations(const ForceModel& model, std::span<const Vec3> x,
                           std::span<const Vec3> v, std::span<const double> inv_mass,
                           std::span<const Vec3> external_force, std::span<Vec3> acceleration) {
  const bool has_external = !external_force.empty();
  const std::size_t n = x.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double w = inv_mass[i];
    if (w == 0.0) {
      acceleration[i].setZero();
      continue;
    }
    Vec3 force = -model.linear_drag * v[i] - model.quadratic_drag * v[i].norm() * v[i];
    if (has_external) force += external_force[i];
    acceleration[i] = model.gravity + w * force;
  }
  for (const Blast& blast : model.blasts) {
    for (std::size_t i = 0; i < n; ++i) {
      if (inv_mass[i] == 0.0) continue;
      const Vec3 d = x[i] - blast.centre;
      const double r = d.norm();
      // At the very centre there is no direction to push: no force rather than a NaN.
      if (r == 0.0 || r >= blast.radius) continue;
      const double f = blast.force * falloffFactor(blast.falloff, r, blast.radius);
      acceleration[i] += (inv_mass[i] * f / r) * d;
    }
  }
  for (const Spring& s : model.springs) {
    const bool anchored = s.b == kWorldAnchor;
    const Vec3 pb = anchored ? s.anchor : x[s.b];
    const Vec3 vb = anchored ? Vec3::Zero() : v[s.b];
    const Vec3 d = pb - x[s.a];
    const double length = d.norm();
    // A zero-length spring has no direction; it exerts no force rather than a NaN.
    if (length == 0.0) continue;
    const Vec3 dir = d / length;
    const double magnitude =
        s.stiffness * (length - s.rest_length) + s.damping * dir.dot(vb - v[s.a]);
    const Vec3 f = magnitude * dir;  // Pulls a towards b when stretched.
    acceleration[s.a] += inv_mass[s.a] * f;
    if (!anchored) acceleration[s.b] -= inv_mass[s.b] * f;
  }
}

}  // namespace zonesim::physics
