#pragma once
// Math types over Eigen. Include only where vector math is done: Eigen is heavy to compile.

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace zonesim {

using Vec3 = Eigen::Vector3d;
using Quat = Eigen::Quaterniond;
using Vec3f = Eigen::Vector3f;

/// The ground-plane (x, z) distance between two points.
inline double planarDistance(const Vec3& a, const Vec3& b) {
  return std::hypot(a.x() - b.x(), a.z() - b.z());
}

/// Integrates an orientation by angular velocity w over dt (first order, renormalised).
inline Quat integrateOrientation(const Quat& q, const Vec3& w, double dt) {
  Quat dq(0.0, w.x() * dt * 0.5, w.y() * dt * 0.5, w.z() * dt * 0.5);
  Quat r = q;
  r.coeffs() += (dq * q).coeffs();
  return r.normalized();
}

}  // namespace zonesim
