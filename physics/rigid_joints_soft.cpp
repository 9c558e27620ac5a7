// Ball and hinge joints under the soft step: at each sub-step a joint's anchors, axes and
// effective masses are rebuilt from the bodies' motion so far in the step (soft_joint_anchor.h);
// the passes then solve the point as one 3x3 block and the hinge's two angular rows one by
// one. The biased pass pulls the error back with the joint spring; the relax pass only stops
// the relative motion.

#include <Eigen/LU>

#include "physics/rigid_joints.h"
#include "physics/solver_row.h"

namespace zonesim::physics {

void RigidJoints::freeze(SoftJoint& joint, const BodyStorage& bodies, std::span<const Vec3> dp,
                         std::span<const Vec3> dtheta, BodyIndex a, BodyIndex b,
                         const Vec3& local_a, const Vec3& local_b) const {
  joint.a = SoftAnchor(bodies, dp, dtheta, a, local_a);
  joint.b = SoftAnchor(bodies, dp, dtheta, b, local_b);
  const Eigen::Matrix3d k = joint.a.inverseMass(bodies) + joint.b.inverseMass(bodies);
  // Both ends immovable: no impulse can help.
  joint.point_mass = k.trace() > 0.0 ? Eigen::Matrix3d(k.inverse()) : Eigen::Matrix3d::Zero();
}

void RigidJoints::prepareSoft(BodyStorage& bodies, std::span<const Vec3> dp,
                              std::span<const Vec3> dtheta) {
  // New joints start from no impulse (joints are only added, at the end).
  soft_.resize(balls_.size() + hinges_.size());
  std::size_t next = 0;
  for (const BallJoint& j : balls_)
    freeze(soft_[next++], bodies, dp, dtheta, j.a, j.b, j.local_a, j.local_b);
  for (const HingeJoint& j : hinges_) {
    SoftJoint& s = soft_[next++];
    freeze(s, bodies, dp, dtheta, j.a, j.b, j.local_a, j.local_b);
    // B's axis tilted away from A's (a_A x a_B) is the error about the two directions
    // perpendicular to A's axis.
    const Vec3 axis_a = SoftAnchor::direction(bodies, dtheta, j.a, j.axis_a);
    const Vec3 tilt = axis_a.cross(SoftAnchor::direction(bodies, dtheta, j.b, j.axis_b));
    s.axis[0] = solver_row::orthogonal(axis_a);
    s.axis[1] = axis_a.cross(s.axis[0]);
    for (int r = 0; r < 2; ++r) {
      const Vec3& u = s.axis[r];
      const double k = s.a.inverseInertia(bodies, u) + s.b.inverseInertia(bodies, u);
      s.axis_mass[r] = k > 0.0 ? 1.0 / k : 0.0;
      s.axis_error[r] = u.dot(tilt);
    }
  }
  for (const SoftJoint& s : soft_) {
    s.a.apply(bodies, -s.linear);
    s.b.apply(bodies, s.linear);
    s.a.applyAngular(bodies, -s.angular);
    s.b.applyAngular(bodies, s.angular);
  }
}

void RigidJoints::iterateSoft(BodyStorage& bodies, const Softness& soft, bool use_bias) {
  const double bias_rate = use_bias ? soft.bias_rate : 0.0;
  const double mass_scale = use_bias ? soft.mass_scale : 1.0;
  const double impulse_scale = use_bias ? soft.impulse_scale : 0.0;
  const std::size_t n_balls = balls_.size();
  for (std::size_t i = 0; i < soft_.size(); ++i) {
    SoftJoint& s = soft_[i];
    if (i >= n_balls) {
      for (int r = 0; r < 2; ++r) {
        const Vec3& u = s.axis[r];
        const double cdot = u.dot(s.b.angularVelocity(bodies) - s.a.angularVelocity(bodies));
        const double lambda = -mass_scale * s.axis_mass[r] * (cdot + bias_rate * s.axis_error[r]) -
                              impulse_scale * u.dot(s.angular);
        s.angular += lambda * u;
        s.a.applyAngular(bodies, -lambda * u);
        s.b.applyAngular(bodies, lambda * u);
      }
    }
    const Vec3 cdot = s.b.velocity(bodies) - s.a.velocity(bodies);
    const Vec3 lambda =
        -mass_scale * (s.point_mass * (cdot + bias_rate * (s.b.point - s.a.point))) -
        impulse_scale * s.linear;
    s.linear += lambda;
    s.a.apply(bodies, -lambda);
    s.b.apply(bodies, lambda);
  }
}

}  // namespace zonesim::physics
