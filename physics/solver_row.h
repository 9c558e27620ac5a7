#pragma once
// Internal to the solvers (contact_solver*.cpp, rigid_joints.cpp): what every contact pass does
// with one Jacobian row, written once so that the Gauss-Seidel, soft, Jacobi, penalty and
// projection passes measure and apply a row with the same floating-point operations in the
// same order; and the one rule that picks a deterministic perpendicular for a basis.

#include <cmath>
#include <span>

#include "common/math.h"

namespace zonesim::physics::solver_row {

/// A unit vector orthogonal to n, chosen by a fixed rule so the basis is deterministic.
inline Vec3 orthogonal(const Vec3& n) {
  const Vec3 helper = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : Vec3::UnitY();
  return n.cross(helper).normalized();
}

/// Relative velocity of B against A along a row's direction d.
inline double relativeVelocity(const Vec3& d, const Vec3& va, const Vec3& wa, const Vec3& vb,
                               const Vec3& wb, const auto& row) {
  return d.dot(vb - va) + row.cb.dot(wb) - row.ca.dot(wa);
}

/// Applies impulse lambda along d of constraint k's row to the linear parts v and angular
/// parts w: the bodies' velocities, or the pseudo-velocities or displacements of a position
/// pass.
inline void applyRow(std::span<Vec3> v, std::span<Vec3> w, const auto& k, const Vec3& d,
                     const auto& row, double lambda) {
  v[k.a] -= (k.ma * lambda) * d;
  w[k.a] -= lambda * row.wa;
  v[k.b] += (k.mb * lambda) * d;
  w[k.b] += lambda * row.wb;
}

}  // namespace zonesim::physics::solver_row
