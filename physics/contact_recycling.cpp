#include "physics/contact_recycling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "physics/aabb.h"
#include "physics/manifold_order.h"

namespace zonesim::physics {

namespace {
// How far a point at unit distance from the rotation's centre moves under rotation q: the chord
// 2 sin(angle / 2) = 2 |vector part| (the same for q and -q).
double chord(const Quat& q) {
  return 2.0 * q.vec().norm();
}
}  // namespace

double boundingRadius(const Shape& shape) {
  if (shape.type == ShapeType::Plane) return std::numeric_limits<double>::infinity();
  // The bounds at the origin contain the shape, so their farthest corner bounds it too.
  const Aabb box = shapeBounds(shape, Vec3::Zero(), Quat::Identity());
  return box.lo.cwiseAbs().cwiseMax(box.hi.cwiseAbs()).norm();
}

double relativeMotionBound(const ManifoldOrigin& then, const Pose& a, const Pose& b,
                           double radius_a, double radius_b, double enough) {
  // The relative rotation (b in a's frame, now against then) turns by the same angle seen from
  // either body.
  const Quat relative_now = a.orientation.conjugate() * b.orientation;
  const Quat relative_then = then.a.orientation.conjugate() * then.b.orientation;
  const double turn = chord(relative_now * relative_then.conjugate());
  // A point x of b sits at t + r x in a's frame; between then and now it moved by
  // (t - t0) + (r - r0) x, whose second term is at most the chord times |x|.
  const Vec3 b_in_a = a.orientation.conjugate() * (b.position - a.position);
  const Vec3 b_in_a_then = then.a.orientation.conjugate() * (then.b.position - then.a.position);
  const double b_moved = (b_in_a - b_in_a_then).norm() + radius_b * turn;
  if (b_moved < enough) return b_moved;
  const Vec3 a_in_b = b.orientation.conjugate() * (a.position - b.position);
  const Vec3 a_in_b_then = then.b.orientation.conjugate() * (then.a.position - then.b.position);
  const double a_moved = (a_in_b - a_in_b_then).norm() + radius_a * turn;
  return std::min(a_moved, b_moved);
}

bool turnedLittle(const ManifoldOrigin& then, const Pose& a, const Pose& b, double max_turn_cos) {
  // cos(angle) = 2 w^2 - 1 for the turn q_now q_then^-1 of unit quaternions.
  const auto cosTurn = [](const Quat& now, const Quat& before) {
    const double w = (now * before.conjugate()).w();
    return 2.0 * w * w - 1.0;
  };
  return cosTurn(a.orientation, then.a.orientation) > max_turn_cos &&
         cosTurn(b.orientation, then.b.orientation) > max_turn_cos;
}

void carryManifold(const ManifoldOrigin& then, const Vec3& normal, int count, const Pose& a,
                   const Pose& b, Manifold& out) {
  // One rotation per body, made a matrix once for all the points.
  const Eigen::Matrix3d turn_a =
      (a.orientation * then.a.orientation.conjugate()).toRotationMatrix();
  const Eigen::Matrix3d turn_b =
      (b.orientation * then.b.orientation.conjugate()).toRotationMatrix();
  for (int i = 0; i < count; ++i) {
    const Vec3 on_a = a.position + turn_a * (then.point[i] - then.a.position);
    const Vec3 on_b = b.position + turn_b * (then.point[i] - then.b.position);
    out.points[i].position = 0.5 * (on_a + on_b);
    out.points[i].depth = then.depth[i] - normal.dot(on_b - on_a);
  }
}

void sortDeepestFirst(Manifold& m, ManifoldOrigin& origin,
                      std::array<std::array<double, 3>, 4>& impulse) {
  sortDeepestFirst(m, [&](int k) {
    std::swap(origin.point[k], origin.point[k - 1]);
    std::swap(origin.depth[k], origin.depth[k - 1]);
    std::swap(impulse[k], impulse[k - 1]);
  });
}

ManifoldOrigin originOf(const Manifold& m, const Pose& a, const Pose& b) {
  ManifoldOrigin o;
  o.a = a;
  o.b = b;
  for (int i = 0; i < m.count; ++i) {
    o.point[i] = m.points[i].position;
    o.depth[i] = m.points[i].depth;
  }
  return o;
}

}  // namespace zonesim::physics
