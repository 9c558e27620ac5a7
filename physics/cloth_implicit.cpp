// Implicit (backward) Euler for the cloth's springs, after Baraff and Witkin ("Large steps in
// cloth simulation", 1998). The sub-step takes the forces at its end, linearised:
//   (M - h df/dv - h^2 df/dx) dv = h (f + h df/dx v),   v += dv,   x += h v.
// Each spring adds a 3x3 block B = h c P + h^2 k (P + max(0, 1 - L/l) (I - P)) (P = d d^T for
// its unit direction d) to the rows of its two particles. The transverse term is clamped at
// zero for compressed springs, whose exact Jacobian would make the matrix indefinite (Choi and
// Ko); the fixed point, the static drape, is unchanged by it. The system is symmetric positive
// definite, so it is solved matrix-free by conjugate gradients with a diagonal preconditioner;
// pinned particles are filtered out (their rows and unknowns are zero).

#include <algorithm>
#include <cmath>

#include "physics/cloth.h"

namespace zonesim::physics {

namespace {

double dot(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i].dot(b[i]);
  return s;
}

}  // namespace

void Cloth::applySystem(const std::vector<Vec3>& p, std::vector<Vec3>& out) const {
  const std::size_t n = x_.size();
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = inv_mass_[i] > 0.0 ? Vec3(p[i] / inv_mass_[i]) : Vec3::Zero();
  }
  for (std::size_t k = 0; k < springs_.size(); ++k) {
    const ClothSpring& s = springs_[k];
    const Vec3 t = blocks_[k] * (p[s.a] - p[s.b]);
    out[s.a] += t;
    out[s.b] -= t;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass_[i] == 0.0) out[i].setZero();
  }
}

void Cloth::stepImplicit(double h) {
  accumulateForces();  // f at the start: gravity, springs and their damping.
  const std::size_t n = x_.size();
  blocks_.resize(springs_.size());
  diagonal_.resize(n);
  r_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double m = inv_mass_[i] > 0.0 ? 1.0 / inv_mass_[i] : 1.0;
    diagonal_[i] = Vec3::Constant(m);
    r_[i] = h * f_[i];
  }
  const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
  for (std::size_t k = 0; k < springs_.size(); ++k) {
    const ClothSpring& s = springs_[k];
    const Vec3 d = x_[s.b] - x_[s.a];
    const double length = d.norm();
    if (length == 0.0) {
      blocks_[k].setZero();  // No direction: no force (accumulateForces) and no stiffness.
      continue;
    }
    const Vec3 dir = d / length;
    const Eigen::Matrix3d along = dir * dir.transpose();
    const double transverse = std::max(0.0, 1.0 - s.rest / length);
    const Eigen::Matrix3d stiffness = s.stiffness * (along + transverse * (identity - along));
    blocks_[k] = h * desc_.spring_damping * along + h * h * stiffness;
    diagonal_[s.a] += blocks_[k].diagonal();
    diagonal_[s.b] += blocks_[k].diagonal();
    // The right-hand side's h^2 df/dx v: spring a is pulled by -K (v_a - v_b).
    const Vec3 t = h * h * (stiffness * (v_[s.a] - v_[s.b]));
    r_[s.a] -= t;
    r_[s.b] += t;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass_[i] == 0.0) r_[i].setZero();
  }
  // Preconditioned conjugate gradients from dv = 0.
  dv_.assign(n, Vec3::Zero());
  z_.resize(n);
  p_.resize(n);
  q_.resize(n);
  const double rhs = std::sqrt(dot(r_, r_));
  cg_iterations_ = 0;
  cg_residual_ = 0.0;
  if (rhs > 0.0) {
    for (std::size_t i = 0; i < n; ++i) z_[i] = r_[i].cwiseQuotient(diagonal_[i]);
    p_ = z_;
    double rz = dot(r_, z_);
    double residual = rhs;
    while (cg_iterations_ < desc_.implicit_max_iterations &&
           residual > desc_.implicit_tolerance * rhs) {
      applySystem(p_, q_);
      const double pq = dot(p_, q_);
      if (!(pq > 0.0)) break;  // Converged to round-off (or a direction with no curvature).
      const double alpha = rz / pq;
      for (std::size_t i = 0; i < n; ++i) {
        dv_[i] += alpha * p_[i];
        r_[i] -= alpha * q_[i];
      }
      ++cg_iterations_;
      residual = std::sqrt(dot(r_, r_));
      for (std::size_t i = 0; i < n; ++i) z_[i] = r_[i].cwiseQuotient(diagonal_[i]);
      const double rz_next = dot(r_, z_);
      const double beta = rz_next / rz;
      rz = rz_next;
      for (std::size_t i = 0; i < n; ++i) p_[i] = z_[i] + beta * p_[i];
    }
    cg_residual_ = residual / rhs;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (inv_mass_[i] == 0.0) continue;
    v_[i] += dv_[i];
    x_[i] += h * v_[i];
  }
}

}  // namespace zonesim::physics
