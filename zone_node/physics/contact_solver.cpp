#include "zone_node/physics/contact_solver.h"

#include <algorithm>
#include <cmath>

namespace zonesim::physics {

namespace {

/// Inverse of the effective mass along direction d at offsets ra, rb.
double inverseMass(const BodyStorage& b, BodyIndex ia, BodyIndex ib, const Vec3& ra, const Vec3& rb,
                   const Vec3& d) {
  const Vec3 ca = ra.cross(d), cb = rb.cross(d);
  return b.inv_mass[ia] + b.inv_mass[ib] + ca.dot(b.inv_inertia_world[ia] * ca) +
         cb.dot(b.inv_inertia_world[ib] * cb);
}

/// A unit vector orthogonal to n, chosen by a fixed rule so the basis is deterministic.
Vec3 orthogonal(const Vec3& n) {
  const Vec3 helper = std::abs(n.x()) < 0.57 ? Vec3::UnitX() : Vec3::UnitY();
  return n.cross(helper).normalized();
}

}  // namespace

void ContactSolver::prepare(const BodyStorage& bodies, std::span<const BodyContact> contacts,
                            const SolverSettings& settings, double dt) {
  settings_ = settings;
  dt_ = dt;
  constraints_.resize(contacts.size());
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const BodyContact& bc = contacts[c];
    Constraint& k = constraints_[c];
    k.a = bc.a;
    k.b = bc.b;
    k.n = bc.manifold.normal;
    k.t[0] = orthogonal(k.n);
    k.t[1] = k.n.cross(k.t[0]);
    k.friction = bc.friction;
    k.count = bc.manifold.count;
    for (int i = 0; i < k.count; ++i) {
      const ContactPoint& cp = bc.manifold.points[i];
      Point& p = k.p[i];
      p.ra = cp.position - bodies.position[k.a];
      p.rb = cp.position - bodies.position[k.b];
      const double kn = inverseMass(bodies, k.a, k.b, p.ra, p.rb, k.n);
      p.normal_mass = kn > 0.0 ? 1.0 / kn : 0.0;
      for (int t = 0; t < 2; ++t) {
        const double kt = inverseMass(bodies, k.a, k.b, p.ra, p.rb, k.t[t]);
        p.tangent_mass[t] = kt > 0.0 ? 1.0 / kt : 0.0;
      }
      p.depth = cp.depth;
      const Vec3 dv = bodies.linear_velocity[k.b] + bodies.angular_velocity[k.b].cross(p.rb) -
                      bodies.linear_velocity[k.a] - bodies.angular_velocity[k.a].cross(p.ra);
      const double vn = dv.dot(k.n);
      // A gap may be closed at gap/dt this step (speculative contact); an impact that closes
      // it within the step bounces by the restitution coefficient.
      const bool impact = vn < -settings.restitution_threshold && -vn * dt >= -cp.depth;
      if (impact && bc.restitution > 0.0) {
        p.target = -bc.restitution * vn;
      } else {
        p.target = cp.depth < 0.0 ? cp.depth / dt : 0.0;
      }
      const bool warm = settings.warm_starting;
      p.jn = warm ? bc.impulse[i][0] : 0.0;
      p.jt[0] = warm ? bc.impulse[i][1] : 0.0;
      p.jt[1] = warm ? bc.impulse[i][2] : 0.0;
      p.jp = 0.0;
    }
  }
}

void ContactSolver::solveVelocities(BodyStorage& bodies, std::span<BodyContact> contacts) {
  auto& v = bodies.linear_velocity;
  auto& w = bodies.angular_velocity;
  const auto& im = bodies.inv_mass;
  const auto& ii = bodies.inv_inertia_world;
  auto apply = [&](const Constraint& k, const Point& p, const Vec3& impulse) {
    v[k.a] -= im[k.a] * impulse;
    w[k.a] -= ii[k.a] * p.ra.cross(impulse);
    v[k.b] += im[k.b] * impulse;
    w[k.b] += ii[k.b] * p.rb.cross(impulse);
  };
  for (const Constraint& k : constraints_) {
    for (int i = 0; i < k.count; ++i) {
      const Point& p = k.p[i];
      apply(k, p, p.jn * k.n + p.jt[0] * k.t[0] + p.jt[1] * k.t[1]);
    }
  }
  for (int it = 0; it < settings_.velocity_iterations; ++it) {
    // All normals first, then all friction with the limits those normals set (as Bullet's
    // sequential impulse solver does): the weight path down a stack converges faster when no
    // friction solve disturbs it in between.
    for (Constraint& k : constraints_) {
      for (int i = 0; i < k.count; ++i) {
        Point& p = k.p[i];
        const Vec3 dv = v[k.b] + w[k.b].cross(p.rb) - v[k.a] - w[k.a].cross(p.ra);
        const double old = p.jn;
        p.jn = std::max(0.0, old - p.normal_mass * (dv.dot(k.n) - p.target));
        apply(k, p, (p.jn - old) * k.n);
      }
    }
    for (Constraint& k : constraints_) {
      for (int i = 0; i < k.count; ++i) {
        Point& p = k.p[i];
        const double limit = k.friction * p.jn;
        for (int t = 0; t < 2; ++t) {
          const Vec3 dv = v[k.b] + w[k.b].cross(p.rb) - v[k.a] - w[k.a].cross(p.ra);
          const double old = p.jt[t];
          p.jt[t] = std::clamp(old - p.tangent_mass[t] * dv.dot(k.t[t]), -limit, limit);
          apply(k, p, (p.jt[t] - old) * k.t[t]);
        }
      }
    }
  }
  for (std::size_t c = 0; c < constraints_.size(); ++c) {
    for (int i = 0; i < constraints_[c].count; ++i) {
      const Point& p = constraints_[c].p[i];
      contacts[c].impulse[i] = {p.jn, p.jt[0], p.jt[1]};
    }
  }
}

void ContactSolver::solvePositions(const BodyStorage& bodies) {
  const std::size_t n = bodies.size();
  ps_v_.assign(n, Vec3::Zero());
  ps_w_.assign(n, Vec3::Zero());
  const auto& im = bodies.inv_mass;
  const auto& ii = bodies.inv_inertia_world;
  const double rate = settings_.split_beta / dt_;
  for (int it = 0; it < settings_.position_iterations; ++it) {
    for (Constraint& k : constraints_) {
      for (int i = 0; i < k.count; ++i) {
        Point& p = k.p[i];
        const double error = p.depth - settings_.slop;
        if (error <= 0.0) continue;
        const Vec3 dv = ps_v_[k.b] + ps_w_[k.b].cross(p.rb) - ps_v_[k.a] - ps_w_[k.a].cross(p.ra);
        const double old = p.jp;
        p.jp = std::max(0.0, old - p.normal_mass * (dv.dot(k.n) - rate * error));
        const Vec3 impulse = (p.jp - old) * k.n;
        ps_v_[k.a] -= im[k.a] * impulse;
        ps_w_[k.a] -= ii[k.a] * p.ra.cross(impulse);
        ps_v_[k.b] += im[k.b] * impulse;
        ps_w_[k.b] += ii[k.b] * p.rb.cross(impulse);
      }
    }
  }
}

}  // namespace zonesim::physics
