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

}  // namespace zonesim::physics
