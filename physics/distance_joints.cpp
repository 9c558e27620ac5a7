#include "physics/distance_joints.h"

#include "physics/soft_joint_anchor.h"

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
    setLinearRow(r, bodies, j.a, j.b, ra, rb, length > 1e-12 ? Vec3(d / length) : Vec3::UnitY());
    r.bias = beta / dt * (length - j.length);
  }
}

void DistanceJoints::warmStart(BodyStorage& bodies) {
  for (std::size_t i = 0; i < joints_.size(); ++i)
    applyRow(rows_[i], bodies, joints_[i].a, joints_[i].b, joints_[i].impulse);
}

void DistanceJoints::iterate(BodyStorage& bodies) {
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    DistanceJoint& j = joints_[i];
    const Row& r = rows_[i];
    const double cdot = rowVelocity(r, bodies, j.a, j.b);
    // Bilateral: the impulse may pull or push, so it is not clamped.
    const double lambda = -r.mass * (cdot + r.bias);
    j.impulse += lambda;
    applyRow(r, bodies, j.a, j.b, lambda);
  }
}

void DistanceJoints::prepareSoft(BodyStorage& bodies, std::span<const Vec3> dp,
                                 std::span<const Vec3> dtheta) {
  soft_.resize(joints_.size());
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    const DistanceJoint& j = joints_[i];
    SoftRow& s = soft_[i];
    s.a = SoftAnchor(bodies, dp, dtheta, j.a, j.local_a);
    s.b = SoftAnchor(bodies, dp, dtheta, j.b, j.local_b);
    const Vec3 d = s.b.point - s.a.point;
    const double length = d.norm();
    // Coincident anchors have no direction; take +y rather than divide by 0.
    s.n = length > 1e-12 ? Vec3(d / length) : Vec3::UnitY();
    s.error = length - j.length;
    const double k = s.a.inverseMassAlong(bodies, s.n) + s.b.inverseMassAlong(bodies, s.n);
    s.mass = k > 0.0 ? 1.0 / k : 0.0;
    s.a.apply(bodies, -j.impulse * s.n);
    s.b.apply(bodies, j.impulse * s.n);
  }
}

void DistanceJoints::iterateSoft(BodyStorage& bodies, const Softness& soft, bool use_bias) {
  const double bias_rate = use_bias ? soft.bias_rate : 0.0;
  const double mass_scale = use_bias ? soft.mass_scale : 1.0;
  const double impulse_scale = use_bias ? soft.impulse_scale : 0.0;
  for (std::size_t i = 0; i < joints_.size(); ++i) {
    DistanceJoint& j = joints_[i];
    const SoftRow& s = soft_[i];
    const double cdot = s.n.dot(s.b.velocity(bodies) - s.a.velocity(bodies));
    const double lambda =
        -mass_scale * s.mass * (cdot + bias_rate * s.error) - impulse_scale * j.impulse;
    j.impulse += lambda;
    s.a.apply(bodies, -lambda * s.n);
    s.b.apply(bodies, lambda * s.n);
  }
}

}  // namespace zonesim::physics
