// The alternative contact responses of SolverKind: projected Jacobi, penalty springs and
// position projection. Gauss-Seidel and SOR share ContactSolver::iterate (contact_solver.cpp),
// the soft step lives in contact_solver_soft.cpp.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "physics/contact_solver.h"
#include "physics/solver_row.h"

namespace zonesim::physics {

using solver_row::applyRow;
using solver_row::relativeVelocity;

void ContactSolver::iterateJacobi(BodyStorage& bodies) {
  auto& v = bodies.linear_velocity;
  auto& w = bodies.angular_velocity;
  const std::size_t n = bodies.size();
  if (row_count_.size() != n) {
    // Points per body, counted once per step (prepare resets the size to zero).
    row_count_.assign(n, 0);
    for (const Constraint& k : constraints_) {
      row_count_[k.a] = static_cast<std::uint16_t>(row_count_[k.a] + k.count);
      row_count_[k.b] = static_cast<std::uint16_t>(row_count_[k.b] + k.count);
    }
  }
  auto scale = [&](const Constraint& k) {
    const int ca = k.ma > 0.0 ? row_count_[k.a] : 0, cb = k.mb > 0.0 ? row_count_[k.b] : 0;
    return 1.0 / std::max(1, std::max(ca, cb));
  };
  // Normals: every update reads the velocities from before the pass.
  for (int pass = 0; pass < 2; ++pass) {
    jac_v_ = bodies.linear_velocity;
    jac_w_ = bodies.angular_velocity;
    for (const Constraint& k : constraints_) {
      const double f = scale(k);
      for (int i = 0; i < k.count; ++i) {
        if (pass == 0) {
          NormalPoint& p = normal_[k.first + i];
          const double vn =
              relativeVelocity(k.n, jac_v_[k.a], jac_w_[k.a], jac_v_[k.b], jac_w_[k.b], p.row);
          const double old = jn_[k.first + i];
          jn_[k.first + i] = std::max(0.0, old - f * p.row.mass * (vn - p.target));
          applyRow(v, w, k, k.n, p.row, jn_[k.first + i] - old);
        } else {
          FrictionPoint& p = friction_[k.first + i];
          const double limit = k.friction * jn_[k.first + i];
          for (int t = 0; t < 2; ++t) {
            const double vt = relativeVelocity(k.t[t], jac_v_[k.a], jac_w_[k.a], jac_v_[k.b],
                                               jac_w_[k.b], p.row[t]);
            const double old = jt_[k.first + i][t];
            jt_[k.first + i][t] = std::clamp(old - f * p.row[t].mass * vt, -limit, limit);
            applyRow(v, w, k, k.t[t], p.row[t], jt_[k.first + i][t] - old);
          }
        }
      }
    }
  }
  // Rolling rows are few (spheres and capsules only) and run Gauss-Seidel after the passes.
  solveRolling(bodies);
}

void ContactSolver::applyPenalty(BodyStorage& bodies) {
  auto& v = bodies.linear_velocity;
  auto& w = bodies.angular_velocity;
  const double omega = 2.0 * std::numbers::pi * settings_.penalty_rate_fraction / dt_;
  const double zeta = settings_.penalty_damping_ratio;
  for (const Constraint& k : constraints_) {
    for (int i = 0; i < k.count; ++i) {
      NormalPoint& p = normal_[k.first + i];
      jn_[k.first + i] = jt_[k.first + i][0] = jt_[k.first + i][1] =
          0.0;  // A penalty force has no memory.
      if (p.depth <= 0.0) continue;
      // Spring k = m omega^2 and damper c = 2 zeta m omega on the row's effective mass m.
      const double vn = relativeVelocity(k.n, v[k.a], w[k.a], v[k.b], w[k.b], p.row);
      const double force = p.row.mass * (omega * omega * p.depth - 2.0 * zeta * omega * vn);
      jn_[k.first + i] = std::max(0.0, force) * dt_;
      applyRow(v, w, k, k.n, p.row, jn_[k.first + i]);
    }
  }
  // Friction: Coulomb rows bounded by mu times each spring's impulse, iterated like PGS
  // friction (one pass leaves a steady creep: measured 1.7 cm/s on a resting box); rolling
  // resistance the same way, bounded by the springs' impulses.
  for (RollingRow& r : rolling_) r.impulse = {0.0, 0.0};
  for (int it = 0; it < settings_.velocity_iterations; ++it) {
    for (const Constraint& k : constraints_) {
      for (int i = 0; i < k.count; ++i) {
        FrictionPoint& fp = friction_[k.first + i];
        const double limit = k.friction * jn_[k.first + i];
        for (int t = 0; t < 2; ++t) {
          const double vt = relativeVelocity(k.t[t], v[k.a], w[k.a], v[k.b], w[k.b], fp.row[t]);
          const double old = jt_[k.first + i][t];
          jt_[k.first + i][t] = std::clamp(old - fp.row[t].mass * vt, -limit, limit);
          applyRow(v, w, k, k.t[t], fp.row[t], jt_[k.first + i][t] - old);
        }
      }
    }
    solveRolling(bodies);
  }
}

void ContactSolver::projectPositions(std::span<Vec3> dp, std::span<Vec3> dtheta) {
  auto move = [&](const Constraint& k, const Vec3& d, const Row& row, double lambda) {
    applyRow(dp, dtheta, k, d, row, lambda);
  };
  for (const Constraint& k : constraints_) {
    for (int i = 0; i < k.count; ++i) {
      NormalPoint& p = normal_[k.first + i];
      // Separation at the displaced anchors; jp accumulates the normal correction (m kg).
      const double s =
          -p.depth + relativeVelocity(k.n, dp[k.a], dtheta[k.a], dp[k.b], dtheta[k.b], p.row);
      const double old = p.jp;
      p.jp = std::max(0.0, old - p.row.mass * s);
      move(k, k.n, p.row, p.jp - old);
      // Static friction as a position constraint (Mueller et al.): undo the tangential slip of
      // this step while the correction stays within mu times the normal correction.
      FrictionPoint& fp = friction_[k.first + i];
      const double limit = k.friction * p.jp;
      for (int t = 0; t < 2; ++t) {
        const double slip =
            relativeVelocity(k.t[t], dp[k.a], dtheta[k.a], dp[k.b], dtheta[k.b], fp.row[t]);
        const double before = jt_[k.first + i][t];
        jt_[k.first + i][t] = std::clamp(before - fp.row[t].mass * slip, -limit, limit);
        move(k, k.t[t], fp.row[t], jt_[k.first + i][t] - before);
      }
    }
  }
}

}  // namespace zonesim::physics
