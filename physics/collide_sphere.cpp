#include "physics/collide_sphere.h"

#include <cmath>

namespace zonesim::physics {

bool collideSpheres(const Vec3& a, double ra, const Vec3& b, double rb, double margin,
                    Manifold& out) {
  const Vec3 d = b - a;
  const double dist = d.norm();
  const double gap = dist - ra - rb;
  if (gap > margin) return false;
  // Coincident centres have no direction; any unit normal is as good, pick +y.
  out.normal = dist > 1e-12 ? Vec3(d / dist) : Vec3::UnitY();
  out.count = 0;
  out.add(a + out.normal * (ra + 0.5 * gap), -gap, 0);
  return true;
}

bool collidePlaneSphere(const Pose& plane, const Vec3& b, double rb, double margin, Manifold& out) {
  const Vec3 n = plane.orientation * Vec3::UnitY();
  const double gap = n.dot(b - plane.position) - rb;
  if (gap > margin) return false;
  out.normal = n;
  out.count = 0;
  out.add(b - n * (rb + 0.5 * gap), -gap, 0);
  return true;
}

bool collideBoxSphere(const Vec3& half, const Pose& box, const Vec3& b, double rb, double margin,
                      Manifold& out) {
  const Vec3 local = box.orientation.conjugate() * (b - box.position);
  const Vec3 clamped = local.cwiseMax(-half).cwiseMin(half);
  Vec3 normal_local;
  double gap;
  std::uint32_t feature = 0;
  if (clamped != local) {
    const Vec3 d = local - clamped;
    const double dist = d.norm();
    gap = dist - rb;
    if (gap > margin) return false;
    normal_local = d / dist;
  } else {
    // Centre inside the box: push out through the nearest face.
    const Vec3 room = half - local.cwiseAbs();
    int axis = 0;
    room.minCoeff(&axis);
    normal_local = Vec3::Zero();
    normal_local[axis] = local[axis] >= 0.0 ? 1.0 : -1.0;
    gap = -room[axis] - rb;
    feature = 1;
  }
  out.normal = box.orientation * normal_local;
  out.count = 0;
  out.add(b - out.normal * (rb + 0.5 * gap), -gap, feature);
  return true;
}

}  // namespace zonesim::physics
