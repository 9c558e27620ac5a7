#include "physics/contact_solver.h"

#include <algorithm>
#include <cmath>

#include "physics/solver_row.h"

namespace zonesim::physics {

using solver_row::applyRow;
using solver_row::orthogonal;
using solver_row::relativeVelocity;

void ContactSolver::prepare(const BodyStorage& bodies, std::span<const BodyContact> contacts,
                            const SolverSettings& settings, double dt) {
  settings_ = settings;
  dt_ = dt;
  constraints_.resize(contacts.size());
  std::size_t points = 0;
  for (const BodyContact& bc : contacts) points += bc.manifold.count;
  normal_.resize(points);
  row_count_.clear();
  friction_.resize(points);
  jn_.resize(points);
  jt_.resize(points);
  rolling_.clear();
  std::uint32_t next = 0;
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const BodyContact& bc = contacts[c];
    Constraint& k = constraints_[c];
    k.a = bc.a;
    k.b = bc.b;
    k.ma = bodies.inv_mass[k.a];
    k.mb = bodies.inv_mass[k.b];
    k.n = bc.manifold.normal;
    k.t[0] = orthogonal(k.n);
    k.t[1] = k.n.cross(k.t[0]);
    k.friction = bc.friction;
    k.restitution = bc.restitution;
    k.first = next;
    k.count = bc.manifold.count;
    next += static_cast<std::uint32_t>(k.count);
    const Eigen::Matrix3d& ia = bodies.inv_inertia_world[k.a];
    const Eigen::Matrix3d& ib = bodies.inv_inertia_world[k.b];
    for (int i = 0; i < k.count; ++i) {
      const ContactPoint& cp = bc.manifold.points[i];
      NormalPoint& np = normal_[k.first + i];
      FrictionPoint& fp = friction_[k.first + i];
      const Vec3 ra = cp.position - bodies.position[k.a];
      const Vec3 rb = cp.position - bodies.position[k.b];
      auto makeRow = [&](const Vec3& d, Row& row) {
        row.ca = ra.cross(d);
        row.cb = rb.cross(d);
        row.wa = ia * row.ca;
        row.wb = ib * row.cb;
        const double inv = k.ma + k.mb + row.ca.dot(row.wa) + row.cb.dot(row.wb);
        row.mass = inv > 0.0 ? 1.0 / inv : 0.0;
      };
      makeRow(k.n, np.row);
      makeRow(k.t[0], fp.row[0]);
      makeRow(k.t[1], fp.row[1]);
      np.depth = cp.depth;
      const double vn =
          relativeVelocity(k.n, bodies.linear_velocity[k.a], bodies.angular_velocity[k.a],
                           bodies.linear_velocity[k.b], bodies.angular_velocity[k.b], np.row);
      // A gap may be closed at gap/dt this step (speculative contact); an impact that closes
      // it within the step bounces by the restitution coefficient.
      const bool impact = vn < -settings.restitution_threshold && -vn * dt >= -cp.depth;
      if (impact && bc.restitution > 0.0) {
        np.target = -bc.restitution * vn;
      } else {
        np.target = cp.depth < 0.0 ? cp.depth / dt : 0.0;
      }
      const bool warm = settings.warm_starting;
      jn_[k.first + i] = warm ? bc.impulse[i][0] : 0.0;
      jt_[k.first + i][0] = warm ? bc.impulse[i][1] : 0.0;
      jt_[k.first + i][1] = warm ? bc.impulse[i][2] : 0.0;
      np.jp = 0.0;
      np.vn0 = vn;
      np.max_jn = 0.0;
    }
    if (bc.rolling > 0.0) {
      RollingRow r;
      r.constraint = static_cast<std::uint32_t>(c);
      r.rolling = bc.rolling;
      for (int t = 0; t < 2; ++t) {
        r.wa[t] = ia * k.t[t];
        r.wb[t] = ib * k.t[t];
        const double inv = k.t[t].dot(r.wa[t]) + k.t[t].dot(r.wb[t]);
        r.mass[t] = inv > 0.0 ? 1.0 / inv : 0.0;
      }
      r.impulse = settings.warm_starting ? bc.rolling_impulse : std::array<double, 2>{};
      rolling_.push_back(r);
    }
  }
}

void ContactSolver::warmStart(BodyStorage& bodies) {
  auto apply = [&](const Constraint& k, const Vec3& d, const Row& row, double lambda) {
    applyRow(bodies.linear_velocity, bodies.angular_velocity, k, d, row, lambda);
  };
  for (const Constraint& k : constraints_) {
    for (int i = 0; i < k.count; ++i) {
      const NormalPoint& np = normal_[k.first + i];
      const FrictionPoint& fp = friction_[k.first + i];
      apply(k, k.n, np.row, jn_[k.first + i]);
      apply(k, k.t[0], fp.row[0], jt_[k.first + i][0]);
      apply(k, k.t[1], fp.row[1], jt_[k.first + i][1]);
    }
  }
  for (const RollingRow& r : rolling_) {
    const Constraint& k = constraints_[r.constraint];
    for (int t = 0; t < 2; ++t) {
      bodies.angular_velocity[k.a] -= r.impulse[t] * r.wa[t];
      bodies.angular_velocity[k.b] += r.impulse[t] * r.wb[t];
    }
  }
}

void ContactSolver::solveRolling(BodyStorage& bodies) {
  auto& w = bodies.angular_velocity;
  for (RollingRow& r : rolling_) {
    const Constraint& k = constraints_[r.constraint];
    double load = 0.0;
    for (int i = 0; i < k.count; ++i) load += jn_[k.first + i];
    const double limit = r.rolling * load;
    // Both tangents from the same velocities, then the pair clamped to a disc: the resistance
    // is the same whichever way the body rolls.
    const std::array<double, 2> old = r.impulse;
    for (int t = 0; t < 2; ++t) {
      r.impulse[t] = old[t] - r.mass[t] * k.t[t].dot(w[k.b] - w[k.a]);
    }
    const double size = std::hypot(r.impulse[0], r.impulse[1]);
    if (size > limit) {
      const double scale = limit > 0.0 ? limit / size : 0.0;
      r.impulse[0] *= scale;
      r.impulse[1] *= scale;
    }
    for (int t = 0; t < 2; ++t) {
      const double delta = r.impulse[t] - old[t];
      w[k.a] -= delta * r.wa[t];
      w[k.b] += delta * r.wb[t];
    }
  }
}

void ContactSolver::iterate(BodyStorage& bodies, double omega) {
  auto& v = bodies.linear_velocity;
  auto& w = bodies.angular_velocity;
  auto apply = [&](const Constraint& k, const Vec3& d, const Row& row, double lambda) {
    applyRow(v, w, k, d, row, lambda);
  };
  // All normals first, then all friction with the limits those normals set (as Bullet's
  // sequential impulse solver does): the weight path down a stack converges faster when no
  // friction solve disturbs it in between.
  for (const Constraint& k : constraints_) {
    for (int i = 0; i < k.count; ++i) {
      NormalPoint& p = normal_[k.first + i];
      const double vn = relativeVelocity(k.n, v[k.a], w[k.a], v[k.b], w[k.b], p.row);
      const double old = jn_[k.first + i];
      jn_[k.first + i] = std::max(0.0, old - omega * p.row.mass * (vn - p.target));
      apply(k, k.n, p.row, jn_[k.first + i] - old);
    }
  }
  for (const Constraint& k : constraints_) {
    for (int i = 0; i < k.count; ++i) {
      FrictionPoint& p = friction_[k.first + i];
      const double limit = k.friction * jn_[k.first + i];
      // A point that carries no load and no friction stays at zero: clamping to [-0, 0] would
      // give zero again, so skip the two rows (most side points in a pile).
      if (limit == 0.0 && jt_[k.first + i][0] == 0.0 && jt_[k.first + i][1] == 0.0) continue;
      for (int t = 0; t < 2; ++t) {
        const Row& row = p.row[t];
        const double vt = relativeVelocity(k.t[t], v[k.a], w[k.a], v[k.b], w[k.b], row);
        const double old = jt_[k.first + i][t];
        jt_[k.first + i][t] = std::clamp(old - omega * row.mass * vt, -limit, limit);
        apply(k, k.t[t], row, jt_[k.first + i][t] - old);
      }
    }
  }
  solveRolling(bodies);
}

void ContactSolver::storeImpulses(std::span<BodyContact> contacts) const {
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    const Constraint& k = constraints_[c];
    for (int i = 0; i < k.count; ++i) {
      contacts[c].impulse[i] = {jn_[k.first + i], jt_[k.first + i][0], jt_[k.first + i][1]};
    }
  }
  for (const RollingRow& r : rolling_) contacts[r.constraint].rolling_impulse = r.impulse;
}

void ContactSolver::solvePositions(const BodyStorage& bodies) {
  const std::size_t n = bodies.size();
  ps_v_.assign(n, Vec3::Zero());
  ps_w_.assign(n, Vec3::Zero());
  const double rate = settings_.split_beta / dt_;
  for (int it = 0; it < settings_.position_iterations; ++it) {
    for (const Constraint& k : constraints_) {
      for (int i = 0; i < k.count; ++i) {
        NormalPoint& p = normal_[k.first + i];
        const double error = p.depth - settings_.slop;
        if (error <= 0.0) continue;
        const double vn =
            relativeVelocity(k.n, ps_v_[k.a], ps_w_[k.a], ps_v_[k.b], ps_w_[k.b], p.row);
        const double old = p.jp;
        p.jp = std::max(0.0, old - p.row.mass * (vn - rate * error));
        applyRow(ps_v_, ps_w_, k, k.n, p.row, p.jp - old);
      }
    }
  }
}

}  // namespace zonesim::physics
