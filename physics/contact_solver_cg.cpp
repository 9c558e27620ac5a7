// Nonsmooth nonlinear conjugate gradients on the contact impulses (Silcowitz, Niebe and
// Erleben, "A nonsmooth nonlinear conjugate gradient method for interactive contact force
// problems", 2010). Projected Gauss-Seidel is a fixed-point map lambda -> PGS(lambda); its
// step lambda - PGS(lambda) plays the gradient of a merit function, and the method adds the
// Fletcher-Reeves momentum beta p to each sweep's result, with beta = |g_k|^2 / |g_k-1|^2 and a
// restart (p = -g) whenever beta > 1. The last iteration of a step is a plain sweep, so the
// impulses the step ends with are projected (no pulling normal, friction within its cone).
// Joints and rolling rows take part in each sweep but not in the momentum.
//
// Contacts that share no movable body are independent problems, so beta and the restarts are
// per group of contacts linked through movable bodies: one global beta mixed every island's
// gradient into every other's step, and an island then ended differently beside others than
// alone (and on one zone than split over several, where islands are stepped apart).

#include <algorithm>
#include <cmath>

#include "physics/contact_solver.h"
#include "physics/solver_row.h"

namespace zonesim::physics {

using solver_row::applyRow;

void ContactSolver::iterateConjugateGradient(BodyStorage& bodies, bool first, bool last) {
  const std::size_t points = jn_.size();
  if (first) {
    // Each constraint's group: contacts linked through movable bodies (a static body links
    // nothing), numbered in order of first appearance.
    cg_sets_.reset(bodies.size());
    for (const Constraint& k : constraints_)
      if (k.ma != 0.0 && k.mb != 0.0) cg_sets_.unite(k.a, k.b);
    constexpr std::uint32_t kNone = ~std::uint32_t(0);
    cg_group_of_root_.assign(bodies.size(), kNone);
    cg_group_.resize(constraints_.size());
    std::uint32_t groups = 0;
    for (std::size_t c = 0; c < constraints_.size(); ++c) {
      const Constraint& k = constraints_[c];
      std::uint32_t& group = cg_group_of_root_[cg_sets_.find(k.ma != 0.0 ? k.a : k.b)];
      if (group == kNone) group = groups++;
      cg_group_[c] = group;
    }
    cg_previous_.assign(groups, 0.0);
    cg_g2_.resize(groups);
    cg_beta_.resize(groups);
    cg_direction_.assign(3 * points, 0.0);
  }
  cg_before_.resize(3 * points);
  for (std::size_t i = 0; i < points; ++i) {
    cg_before_[3 * i] = jn_[i];
    cg_before_[3 * i + 1] = jt_[i][0];
    cg_before_[3 * i + 2] = jt_[i][1];
  }
  iterate(bodies, 1.0);
  // g = lambda_before - PGS(lambda_before), kept in cg_before_; |g|^2 per group.
  std::fill(cg_g2_.begin(), cg_g2_.end(), 0.0);
  double all = 0.0;
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    const Constraint& k = constraints_[c];
    double& g2 = cg_g2_[cg_group_[c]];
    for (int p = 0; p < k.count; ++p) {
      const std::size_t i = k.first + p;
      cg_before_[3 * i] -= jn_[i];
      cg_before_[3 * i + 1] -= jt_[i][0];
      cg_before_[3 * i + 2] -= jt_[i][1];
      for (int r = 0; r < 3; ++r) g2 += cg_before_[3 * i + r] * cg_before_[3 * i + r];
    }
  }
  for (std::size_t g = 0; g < cg_g2_.size(); ++g) {
    all += cg_g2_[g];
    double beta = !first && cg_previous_[g] > 0.0 ? cg_g2_[g] / cg_previous_[g] : 0.0;
    // Restart (beta 0, the direction forgotten) when it became worse than steepest descent.
    if (beta > 1.0) beta = -1.0;
    cg_beta_[g] = beta;
    cg_previous_[g] = cg_g2_[g];
  }
  cg_change_ = std::sqrt(all);
  auto& v = bodies.linear_velocity;
  auto& w = bodies.angular_velocity;
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    const Constraint& k = constraints_[c];
    double& beta = cg_beta_[cg_group_[c]];
    const double step = std::max(beta, 0.0);
    for (int p = 0; p < k.count; ++p) {
      const std::size_t at = k.first + p;
      // lambda += beta p, with the velocities following the impulses.
      if (!last && step > 0.0) {
        const double dn = step * cg_direction_[3 * at];
        jn_[at] += dn;
        applyRow(v, w, k, k.n, normal_[at].row, dn);
        for (int t = 0; t < 2; ++t) {
          const double dt = step * cg_direction_[3 * at + 1 + t];
          jt_[at][t] += dt;
          applyRow(v, w, k, k.t[t], friction_[at].row[t], dt);
        }
      }
      // p = beta p - g (a restart forgets p).
      for (int r = 0; r < 3; ++r)
        cg_direction_[3 * at + r] = step * cg_direction_[3 * at + r] - cg_before_[3 * at + r];
    }
  }
}

}  // namespace zonesim::physics
