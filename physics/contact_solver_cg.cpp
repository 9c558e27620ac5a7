// Nonsmooth nonlinear conjugate gradients on the contact impulses (Silcowitz, Niebe and
// Erleben, "A nonsmooth nonlinear conjugate gradient method for interactive contact force
// problems", 2010). Projected Gauss-Seidel is a fixed-point map lambda -> PGS(lambda); its
// step lambda - PGS(lambda) plays the gradient of a merit function, and the method adds the
// Fletcher-Reeves momentum beta p to each sweep's result, with beta = |g_k|^2 / |g_k-1|^2 and a
// restart (p = -g) whenever beta > 1. The last iteration of a step is a plain sweep, so the
// impulses the step ends with are projected (no pulling normal, friction within its cone).
// Joints and rolling rows take part in each sweep but not in the momentum.

#include <algorithm>
#include <cmath>

#include "physics/contact_solver.h"
#include "physics/solver_row.h"

namespace zonesim::physics {

using solver_row::applyRow;

void ContactSolver::iterateConjugateGradient(BodyStorage& bodies, bool first, bool last) {
  const std::size_t points = jn_.size();
  cg_before_.resize(3 * points);
  for (std::size_t i = 0; i < points; ++i) {
    cg_before_[3 * i] = jn_[i];
    cg_before_[3 * i + 1] = jt_[i][0];
    cg_before_[3 * i + 2] = jt_[i][1];
  }
  iterate(bodies, 1.0);
  // g = lambda_before - PGS(lambda_before), kept in cg_before_.
  double g2 = 0.0;
  for (std::size_t i = 0; i < points; ++i) {
    cg_before_[3 * i] -= jn_[i];
    cg_before_[3 * i + 1] -= jt_[i][0];
    cg_before_[3 * i + 2] -= jt_[i][1];
    for (int r = 0; r < 3; ++r) g2 += cg_before_[3 * i + r] * cg_before_[3 * i + r];
  }
  cg_change_ = std::sqrt(g2);
  double beta = 0.0;
  if (!first && cg_previous_ > 0.0) beta = g2 / cg_previous_;
  if (beta > 1.0 || first) {
    beta = 0.0;  // Restart: the direction became worse than steepest descent.
    cg_direction_.assign(3 * points, 0.0);
  }
  cg_previous_ = g2;
  if (!last && beta > 0.0) {
    // lambda += beta p, with the velocities following the impulses.
    auto& v = bodies.linear_velocity;
    auto& w = bodies.angular_velocity;
    for (const Constraint& k : constraints_) {
      for (int i = 0; i < k.count; ++i) {
        const std::size_t at = k.first + i;
        const double dn = beta * cg_direction_[3 * at];
        jn_[at] += dn;
        applyRow(v, w, k, k.n, normal_[at].row, dn);
        for (int t = 0; t < 2; ++t) {
          const double dt = beta * cg_direction_[3 * at + 1 + t];
          jt_[at][t] += dt;
          applyRow(v, w, k, k.t[t], friction_[at].row[t], dt);
        }
      }
    }
  }
  // p = beta p - g.
  for (std::size_t i = 0; i < cg_direction_.size(); ++i) {
    cg_direction_[i] = beta * cg_direction_[i] - cg_before_[i];
  }
}

}  // namespace zonesim::physics
