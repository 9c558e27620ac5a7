#pragma once
// A joint anchor as the soft step sees it: bodies keep their start-of-step pose during the
// step's sub-steps while their motion so far accumulates in dp and dtheta, so an anchor's
// current offset and point are the start ones moved by that motion. Joints recompute their
// directions and effective masses from these at every pass (as Box2D v3 does): a chain link
// whipping round by a radian in one step keeps its constraint where its anchors are.

#include <Eigen/Geometry>
#include <span>

#include "common/math.h"
#include "physics/body_storage.h"
#include "physics/joint_row.h"

namespace zonesim::physics {

/// v turned by the rotation vector dtheta (exact, by its angle and axis).
inline Vec3 rotatedBy(const Vec3& dtheta, const Vec3& v) {
  const double angle = dtheta.norm();
  if (angle < 1e-12) return v + dtheta.cross(v);
  return Eigen::AngleAxisd(angle, dtheta / angle) * v;
}

/// q turned by the rotation vector dtheta (exact), normalised.
inline Quat rotatedBy(const Vec3& dtheta, const Quat& q) {
  const double angle = dtheta.norm();
  if (angle < 1e-12) return integrateOrientation(q, dtheta, 1.0);
  return (Quat(Eigen::AngleAxisd(angle, dtheta / angle)) * q).normalized();
}

/// One end of a joint during a soft step: the body (or kNoBody for a world point), the
/// anchor's offset from the body's centre and the anchor point, both at the current motion.
struct SoftAnchor {
  BodyIndex body = kNoBody;
  Vec3 r = Vec3::Zero();
  Vec3 point = Vec3::Zero();

  SoftAnchor() = default;
  /// The anchor local (in the body's frame; a world point when body is kNoBody).
  SoftAnchor(const BodyStorage& bodies, std::span<const Vec3> dp, std::span<const Vec3> dtheta,
             BodyIndex i, const Vec3& local)
      : body(i) {
    if (i == kNoBody) {
      point = local;
      return;
    }
    r = rotatedBy(dtheta[i], bodies.orientation[i] * local);
    point = bodies.position[i] + dp[i] + r;
  }
  /// The anchor point's velocity.
  Vec3 velocity(const BodyStorage& bodies) const {
    if (body == kNoBody) return Vec3::Zero();
    return bodies.linear_velocity[body] + bodies.angular_velocity[body].cross(r);
  }
  /// A direction turned by this body's motion so far (a world direction when fixed).
  static Vec3 direction(const BodyStorage& bodies, std::span<const Vec3> dtheta, BodyIndex i,
                        const Vec3& local) {
    if (i == kNoBody) return local;
    return rotatedBy(dtheta[i], bodies.orientation[i] * local);
  }
  /// The anchor's inverse mass matrix: how its velocity answers an impulse applied there.
  Eigen::Matrix3d inverseMass(const BodyStorage& bodies) const {
    if (body == kNoBody) return Eigen::Matrix3d::Zero();
    Eigen::Matrix3d skew;
    skew << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    return bodies.inv_mass[body] * Eigen::Matrix3d::Identity() -
           skew * bodies.inv_inertia_world[body] * skew;
  }
  /// Applies impulse p at the anchor (sign +1) or its reaction (sign -1).
  void apply(BodyStorage& bodies, const Vec3& p) const {
    if (body == kNoBody) return;
    bodies.linear_velocity[body] += bodies.inv_mass[body] * p;
    bodies.angular_velocity[body] += bodies.inv_inertia_world[body] * r.cross(p);
  }
  /// Applies angular impulse l to the body.
  void applyAngular(BodyStorage& bodies, const Vec3& l) const {
    if (body == kNoBody) return;
    bodies.angular_velocity[body] += bodies.inv_inertia_world[body] * l;
  }
  /// How the anchor's velocity along the unit n answers a unit impulse along n.
  double inverseMassAlong(const BodyStorage& bodies, const Vec3& n) const {
    if (body == kNoBody) return 0.0;
    const Vec3 c = r.cross(n);
    return bodies.inv_mass[body] + c.dot(bodies.inv_inertia_world[body] * c);
  }
  /// The body's angular velocity (zero for a world point).
  Vec3 angularVelocity(const BodyStorage& bodies) const {
    return body == kNoBody ? Vec3::Zero() : Vec3(bodies.angular_velocity[body]);
  }
  /// u . I^-1 u: the body's inverse inertia about the direction u.
  double inverseInertia(const BodyStorage& bodies, const Vec3& u) const {
    if (body == kNoBody) return 0.0;
    return u.dot(bodies.inv_inertia_world[body] * u);
  }
};

}  // namespace zonesim::physics
