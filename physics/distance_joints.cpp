#include "physics/distance_joints.h"

namespace zonesim::physics {

std::uint32_t DistanceJoints::add(const DistanceJoint& joint) {
  joints_.push_back(joint);
  return static_cast<std::uint32_t>(joints_.size() - 1);
}

void DistanceJoints::prepare(const BodyStorage& bodies, double dt, double beta) {
  rows_.resize(joints_.size());
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const DistanceJoint& j = joints_[i];
    Row& r = rows_[i];
    const Vec3 ra = bodies.orientation[j.a] * j.local_a;
    const Vec3 pa = bodies.position[j.a] + ra;
    const bool fixed = j.b == kNoBody;
    const Vec3 rb = fixed ? Vec3::Zero() : Vec3(bodies.orientation[j.b] * j.local_b);
    const Vec3 pb = fixed ? j.local_b : Vec3(bodies.position[j.b] + rb);
    const Vec3 d = pb - pa;
    const double length = d.norm();
    // Coincident anchors have no direction; keep last step's (or +y) rather than divide by 0.
    r.n = length > 1e-12 ? Vec3(d / length) : Vec3::UnitY();
    r.ca = ra.cross(r.n);
    r.cb = rb.cross(r.n);
    r.wa = bodies.inv_inertia_world[j.a] * r.ca;
    r.wb = fixed ? Vec3::Zero() : Vec3(bodies.inv_inertia_world[j.b] * r.cb);
    r.ma = bodies.inv_mass[j.a];
    r.mb = fixed ? 0.0 : bodies.inv_mass[j.b];
    const double inv = r.ma + r.mb + r.ca.dot(r.wa) + r.cb.dot(r.wb);
    r.mass = inv > 0.0 ? 1.0 / inv : 0.0;
    r.bias = beta / dt * (length - j.length);
  }
}

void DistanceJoints::apply(BodyStorage& bodies, const DistanceJoint& j, const Row& r,
                           double lambda) const {
  bodies.linear_velocity[j.a] -= (r.ma * lambda) * r.n;
  bodies.angular_velocity[j.a] -= lambda * r.wa;
  if (j.b == kNoBody) return;
  bodies.linear_velocity[j.b] += (r.mb * lambda) * r.n;
  bodies.angular_velocity[j.b] += lambda * r.wb;
}

void DistanceJoints::warmStart(BodyStorage& bodies) {
  for (std::size_t i = 0; i < joints_.size(); ++i)
    apply(bodies, joints_[i], rows_[i], joints_[i].impulse);
}

void DistanceJoints::iterate(BodyStorage& bodies) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    DistanceJoint& j = joints_[i];
    const Row& r = rows_[i];
    const bool fixed = j.b == kNoBody;
    const Vec3 vb = fixed ? Vec3::Zero() : bodies.linear_velocity[j.b];
    const Vec3 wb = fixed ? Vec3::Zero() : bodies.angular_velocity[j.b];
    const double cdot = r.n.dot(vb - bodies.linear_velocity[j.a]) + r.cb.dot(wb) -
                        r.ca.dot(bodies.angular_velocity[j.a]);
    // Bilateral: the impulse may pull or push, so it is not clamped.
    const double lambda = -r.mass * (cdot + r.bias);
    j.impulse += lambda;
    apply(bodies, j, r, lambda);
  }
}

}  // namespace zonesim::physics
