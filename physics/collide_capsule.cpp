#include "physics/collide_capsule.h"

#include <algorithm>

#include "physics/collide_sphere.h"

namespace zonesim::physics {

namespace {

struct Segment {
  Vec3 p0, p1;
};

Segment segmentOf(const Shape& capsule, const Pose& pose) {
  const Vec3 axis = pose.orientation * Vec3(0, capsule.half_height, 0);
  return Segment{pose.position - axis, pose.position + axis};
}

Vec3 closestOnSegment(const Segment& s, const Vec3& p) {
  const Vec3 d = s.p1 - s.p0;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp(d.dot(p - s.p0) / len2, 0.0, 1.0) : 0.0;
  return s.p0 + t * d;
}

/// Closest points between two segments (Ericson, Real-Time Collision Detection 5.1.9).
void closestBetweenSegments(const Segment& a, const Segment& b, Vec3& qa, Vec3& qb) {
  const Vec3 d1 = a.p1 - a.p0, d2 = b.p1 - b.p0, r = a.p0 - b.p0;
  const double aa = d1.squaredNorm(), ee = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (aa <= 1e-12 && ee <= 1e-12) {
  } else if (aa <= 1e-12) {
    t = std::clamp(f / ee, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (ee <= 1e-12) {
      s = std::clamp(-c / aa, 0.0, 1.0);
    } else {
      const double bb = d1.dot(d2), den = aa * ee - bb * bb;
      s = den > 1e-12 ? std::clamp((bb * f - c * ee) / den, 0.0, 1.0) : 0.0;
      t = (bb * s + f) / ee;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / aa, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((bb - c) / aa, 0.0, 1.0);
      }
    }
  }
  qa = a.p0 + s * d1;
  qb = b.p0 + t * d2;
}

/// Adds sphere-pair contacts measured along a shared normal, so that all points agree.
void addAlongNormal(const Vec3& pa, double ra, const Vec3& pb, double rb, std::uint32_t feature,
                    double margin, Manifold& out) {
  const double gap = out.normal.dot(pb - pa) - ra - rb;
  if (gap <= margin) out.add(pa + out.normal * (ra + 0.5 * gap), -gap, feature);
}

}  // namespace

bool collideCapsuleSphere(const Shape& capsule, const Pose& a, const Vec3& b, double rb,
                          double margin, Manifold& out) {
  const Vec3 q = closestOnSegment(segmentOf(capsule, a), b);
  return collideSpheres(q, capsule.radius, b, rb, margin, out);
}

bool collidePlaneCapsule(const Pose& plane, const Shape& capsule, const Pose& b, double margin,
                         Manifold& out) {
  const Segment s = segmentOf(capsule, b);
  out.normal = plane.orientation * Vec3::UnitY();
  out.count = 0;
  for (std::uint32_t k = 0; k < 2; ++k) {
    const Vec3& p = k == 0 ? s.p0 : s.p1;
    const double gap = out.normal.dot(p - plane.position) - capsule.radius;
    if (gap <= margin) out.add(p - out.normal * (capsule.radius + 0.5 * gap), -gap, k);
  }
  return out.count > 0;
}

bool collideCapsules(const Shape& ca, const Pose& a, const Shape& cb, const Pose& b, double margin,
                     Manifold& out) {
  const Segment sa = segmentOf(ca, a), sb = segmentOf(cb, b);
  Vec3 qa, qb;
  closestBetweenSegments(sa, sb, qa, qb);
  if (!collideSpheres(qa, ca.radius, qb, cb.radius, margin, out)) return false;
  const Vec3 da = sa.p1 - sa.p0, db = sb.p1 - sb.p0;
  const double la = da.norm(), lb = db.norm();
  // Lying side by side: one point cannot hold a capsule resting on another, use both ends of
  // B's overlap with A.
  if (la > 1e-9 && lb > 1e-9 && da.cross(db).norm() < 1e-3 * la * lb) {
    out.count = 0;
    for (std::uint32_t k = 0; k < 2; ++k) {
      const Vec3& pb = k == 0 ? sb.p0 : sb.p1;
      addAlongNormal(closestOnSegment(sa, pb), ca.radius, pb, cb.radius, k, margin, out);
    }
    if (out.count == 0) return collideSpheres(qa, ca.radius, qb, cb.radius, margin, out);
  }
  return true;
}

bool collideBoxCapsule(const Vec3& half, const Pose& box, const Shape& capsule, const Pose& b,
                       double margin, Manifold& out) {
  const Segment s = segmentOf(capsule, b);
  // The segment point closest to the box: alternate projections between the two convex sets
  // (converges to the closest pair when they are apart; a few rounds suffice for contact).
  const Quat inv = box.orientation.conjugate();
  Vec3 on_segment = closestOnSegment(s, box.position);
  for (int round = 0; round < 4; ++round) {
    const Vec3 local = inv * (on_segment - box.position);
    const Vec3 on_box = box.position + box.orientation * local.cwiseMax(-half).cwiseMin(half);
    on_segment = closestOnSegment(s, on_box);
  }
  Manifold probe;
  if (!collideBoxSphere(half, box, on_segment, capsule.radius, margin, probe)) return false;
  out.normal = probe.normal;
  out.count = 0;
  // Every candidate is measured along the closest point's normal: one normal per manifold.
  const Vec3 candidates[3] = {s.p0, s.p1, on_segment};
  for (std::uint32_t k = 0; k < 3; ++k) {
    Manifold m;
    if (!collideBoxSphere(half, box, candidates[k], capsule.radius, margin, m)) continue;
    if (m.normal.dot(out.normal) < 0.999) continue;
    out.add(m.points[0].position, m.points[0].depth, k);
  }
  if (out.count == 0) out.add(probe.points[0].position, probe.points[0].depth, 2);
  return true;
}

}  // namespace zonesim::physics
