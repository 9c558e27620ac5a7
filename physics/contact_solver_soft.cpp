// The soft step (Box2D v3's solver): sub-stepped, soft-biased and relaxed contact passes.
//
// Why it holds stacks where plain PGS does not: each sub-step applies the gravity of only
// dt/N, warm starts, solves once and moves the bodies, so a column's weight is carried by the
// previous sub-step's impulses instead of waiting for ten Gauss-Seidel sweeps to carry it down.
// Overlap is pushed out by a stiff, heavily damped spring (the bias) whose velocity the relax
// pass then removes, so the push does not turn into kinetic energy (like split impulses).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "physics/contact_solver.h"
#include "physics/solver_row.h"

namespace zonesim::physics {

using solver_row::applyRow;
using solver_row::relativeVelocity;

void ContactSolver::solveSoft(BodyStorage& bodies, std::span<const Vec3> dp,
                              std::span<const Vec3> dtheta, const Softness& soft,
                              const Softness& soft_static, bool use_bias, double inv_h) {
  auto& v = bodies.linear_velocity;
  auto& w = bodies.angular_velocity;
  const double max_push = settings_.max_push_velocity;
  const auto normals = [&](const Constraint& k) {
    // Separation moves with the relative displacement of the anchors (small-angle rotation).
    const double moved = k.n.dot(dp[k.b] - dp[k.a]);
    const Softness& spring = (k.ma == 0.0 || k.mb == 0.0) ? soft_static : soft;
    for (int i = 0; i < k.count; ++i) {
      NormalPoint& p = normal_[k.first + i];
      const double s = -p.depth + moved + p.row.cb.dot(dtheta[k.b]) - p.row.ca.dot(dtheta[k.a]);
      double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
      if (s > 0.0) {
        bias = s * inv_h;  // Speculative: may close the gap within this sub-step.
      } else if (use_bias) {
        // No slop: the soft spring's own static deflection already keeps contacts alive.
        bias = std::max(spring.bias_rate * s, -max_push);
        mass_scale = spring.mass_scale;
        impulse_scale = spring.impulse_scale;
      }
      const double vn = relativeVelocity(k.n, v[k.a], w[k.a], v[k.b], w[k.b], p.row);
      const double old = jn_[k.first + i];
      const double delta = -p.row.mass * mass_scale * (vn + bias) - impulse_scale * old;
      jn_[k.first + i] = std::max(0.0, old + delta);
      p.max_jn = std::max(p.max_jn, jn_[k.first + i]);
      applyRow(v, w, k, k.n, p.row, jn_[k.first + i] - old);
    }
  };
  // Friction for every contact first, then the normals: the normals, which keep bodies out of
  // each other, have the last word, and friction limits come from the previous pass's normal
  // impulses. In the other orders Box3D's pyramid creeps sideways until it falls (base 20,
  // 2,000 steps of 4 sub-steps: 2.96 m normals first, 0.11 m contact by contact, 2.7 mm
  // this way; `physics_vs_bullet creep`, docs/benchmarks.md), while the columns and mass-ratio
  // stacks stay under 4 mm.
  const auto friction = [&](const Constraint& k) {
    for (int i = 0; i < k.count; ++i) {
      FrictionPoint& p = friction_[k.first + i];
      const double limit = k.friction * jn_[k.first + i];
      // Both tangents from the same velocities, then the pair clamped to the Coulomb disc.
      double j[2], old[2];
      for (int t = 0; t < 2; ++t) {
        const Row& row = p.row[t];
        const double vt = relativeVelocity(k.t[t], v[k.a], w[k.a], v[k.b], w[k.b], row);
        old[t] = jt_[k.first + i][t];
        j[t] = old[t] - row.mass * vt;
      }
      const double size2 = j[0] * j[0] + j[1] * j[1];
      const double scale = size2 > limit * limit ? limit / std::sqrt(size2) : 1.0;
      for (int t = 0; t < 2; ++t) {
        jt_[k.first + i][t] = j[t] * scale;
        applyRow(v, w, k, k.t[t], p.row[t], jt_[k.first + i][t] - old[t]);
      }
    }
  };
  for (const Constraint& k : constraints_) friction(k);
  for (const Constraint& k : constraints_) normals(k);
  solveRolling(bodies);
}

void ContactSolver::applyRestitution(BodyStorage& bodies) {
  auto& v = bodies.linear_velocity;
  auto& w = bodies.angular_velocity;
  const double threshold = settings_.restitution_threshold;
  for (const Constraint& k : constraints_) {
    if (k.restitution == 0.0) continue;
    for (int i = 0; i < k.count; ++i) {
      NormalPoint& p = normal_[k.first + i];
      // Only points that were approaching fast and actually pushed this step bounce.
      if (p.vn0 > -threshold || p.max_jn == 0.0) continue;
      const double vn = relativeVelocity(k.n, v[k.a], w[k.a], v[k.b], w[k.b], p.row);
      const double old = jn_[k.first + i];
      jn_[k.first + i] = std::max(0.0, old - p.row.mass * (vn + k.restitution * p.vn0));
      applyRow(v, w, k, k.n, p.row, jn_[k.first + i] - old);
    }
  }
}

}  // namespace zonesim::physics
