#pragma once
// One bilateral joint row, shared by the distance joints and the ball and hinge joints: its
// setup along a linear direction, its velocity error and its impulse are written once, so
// that every joint kind solves a row with the same operations in the same order.

#include <limits>

#include "common/math.h"
#include "physics/body_storage.h"

namespace zonesim::physics {

/// Marks a joint end fixed in the world rather than on a body.
inline constexpr BodyIndex kNoBody = std::numeric_limits<BodyIndex>::max();

/// One row of a joint between bodies a and b (b may be kNoBody: no velocity, mass or inertia).
struct JointRow {
  Vec3 d;         ///< Linear direction (zero for an angular row).
  Vec3 ca, cb;    ///< ra x d, rb x d (the axis itself for an angular row).
  Vec3 wa, wb;    ///< I_a^-1 ca, I_b^-1 cb.
  double ma, mb;  ///< Inverse masses (zero for an angular row).
  double mass;    ///< 1 / (effective inverse mass of the row).
  double bias;    ///< Velocity the row aims for, from the position error.
};

/// Sets r up along the unit direction d for anchors ra, rb (from the bodies' centres, in world
/// axes); r.bias is left to the caller.
inline void setLinearRow(JointRow& r, const BodyStorage& bodies, BodyIndex a, BodyIndex b,
                         const Vec3& ra, const Vec3& rb, const Vec3& d) {
  const bool fixed = b == kNoBody;
  r.d = d;
  r.ca = ra.cross(r.d);
  r.cb = rb.cross(r.d);
  r.wa = bodies.inv_inertia_world[a] * r.ca;
  r.wb = fixed ? Vec3::Zero() : Vec3(bodies.inv_inertia_world[b] * r.cb);
  r.ma = bodies.inv_mass[a];
  r.mb = fixed ? 0.0 : bodies.inv_mass[b];
  const double inv = r.ma + r.mb + r.ca.dot(r.wa) + r.cb.dot(r.wb);
  r.mass = inv > 0.0 ? 1.0 / inv : 0.0;
}

/// The row's relative velocity: b's against a's along d and the angular parts.
inline double rowVelocity(const JointRow& r, const BodyStorage& bodies, BodyIndex a, BodyIndex b) {
  const bool fixed = b == kNoBody;
  const Vec3 vb = fixed ? Vec3::Zero() : bodies.linear_velocity[b];
  const Vec3 wb = fixed ? Vec3::Zero() : bodies.angular_velocity[b];
  return r.d.dot(vb - bodies.linear_velocity[a]) + r.cb.dot(wb) -
         r.ca.dot(bodies.angular_velocity[a]);
}

/// Applies impulse lambda along the row to the bodies' velocities.
inline void applyRow(const JointRow& r, BodyStorage& bodies, BodyIndex a, BodyIndex b,
                     double lambda) {
  bodies.linear_velocity[a] -= (r.ma * lambda) * r.d;
  bodies.angular_velocity[a] -= lambda * r.wa;
  if (b == kNoBody) return;
  bodies.linear_velocity[b] += (r.mb * lambda) * r.d;
  bodies.angular_velocity[b] += lambda * r.wb;
}

}  // namespace zonesim::physics
