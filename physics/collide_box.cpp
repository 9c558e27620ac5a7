#include "physics/collide_box.h"

#include <cmath>
#include <limits>

#include "physics/clip.h"

namespace zonesim::physics {

namespace {

/// Keeps the points within margin, reduced to four, as the manifold (normal already set).
/// The points are on the incident surface; sep is their gap along the normal ref_n.
void emit(const Vec3* points, const double* sep, const std::uint32_t* feature, int count,
          const Vec3& ref_n, double margin, Manifold& out) {
  Vec3 kept_p[8];
  double kept_depth[8];
  std::uint32_t kept_f[8];
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    if (sep[i] > margin) continue;
    // The midpoint between the incident point and its projection on the reference surface.
    kept_p[kept] = points[i] - 0.5 * sep[i] * ref_n;
    kept_depth[kept] = -sep[i];
    kept_f[kept] = feature[i];
    ++kept;
  }
  out.count = 0;
  if (kept <= 4) {
    for (int i = 0; i < kept; ++i) out.add(kept_p[i], kept_depth[i], kept_f[i]);
    return;
  }
  int keep[4];
  reduceToFour(kept_p, kept_depth, kept, ref_n, keep);
  for (int k = 0; k < 4; ++k) {
    bool seen = false;
    for (int m = 0; m < k; ++m) seen = seen || keep[m] == keep[k];
    if (!seen) out.add(kept_p[keep[k]], kept_depth[keep[k]], kept_f[keep[k]]);
  }
}

/// Separation of two boxes along a unit axis (negative: overlap depth).
double separation(const Vec3& axis, const Vec3& d, const Eigen::Matrix3d& ra, const Vec3& ha,
                  const Eigen::Matrix3d& rb, const Vec3& hb) {
  const double pa = (ra.transpose() * axis).cwiseAbs().dot(ha);
  const double pb = (rb.transpose() * axis).cwiseAbs().dot(hb);
  return std::abs(axis.dot(d)) - pa - pb;
}

double signOf(double x) {
  return x >= 0.0 ? 1.0 : -1.0;
}

/// Clips the incident box's face against reference face `axis` of the reference box.
void faceContact(const Eigen::Matrix3d& rr, const Vec3& cr, const Vec3& hr, int axis,
                 const Eigen::Matrix3d& ri, const Vec3& ci, const Vec3& hi, bool ref_is_b,
                 double margin, Manifold& out) {
  const double s = signOf(rr.col(axis).dot(ci - cr));
  const Vec3 ref_n = s * rr.col(axis);  // Outward normal of the reference face, to the other.
  // Incident face: the face of the other box most anti-parallel to ref_n.
  int inc = 0;
  (ri.transpose() * ref_n).cwiseAbs().maxCoeff(&inc);
  const double inc_sign = -signOf(ri.col(inc).dot(ref_n));
  const int k = (inc + 1) % 3, l = (inc + 2) % 3;
  const Vec3 face = ci + inc_sign * hi[inc] * ri.col(inc);
  const Vec3 u = hi[k] * ri.col(k), v = hi[l] * ri.col(l);
  ClipVertex poly[16], scratch[16];
  poly[0] = {face + u + v, 0};
  poly[1] = {face - u + v, 1};
  poly[2] = {face - u - v, 2};
  poly[3] = {face + u - v, 3};
  int count = 4;
  const int rk = (axis + 1) % 3, rl = (axis + 2) % 3;
  const Vec3 side[4] = {rr.col(rk), -rr.col(rk), rr.col(rl), -rr.col(rl)};
  const double extent[4] = {hr[rk], hr[rk], hr[rl], hr[rl]};
  for (std::uint32_t p = 0; p < 4 && count > 0; ++p) {
    count = clipPolygon(poly, count, side[p], side[p].dot(cr) + extent[p], p, scratch);
    for (int i = 0; i < count; ++i) poly[i] = scratch[i];
  }
  const double ref_offset = ref_n.dot(cr) + hr[axis];
  Vec3 points[8];
  double sep[8];
  std::uint32_t feature[8];
  // Which reference and incident faces: part of the id, so a face switch resets warm starts.
  const std::uint32_t faces =
      ((ref_is_b ? 6u : 0u) + axis * 2 + (s > 0) + 12u * (inc * 2 + (inc_sign > 0))) << 8;
  for (int i = 0; i < count && i < 8; ++i) {
    points[i] = poly[i].p;
    sep[i] = ref_n.dot(poly[i].p) - ref_offset;
    feature[i] = faces | poly[i].feature;
  }
  out.normal = ref_is_b ? Vec3(-ref_n) : ref_n;
  emit(points, sep, feature, std::min(count, 8), ref_n, margin, out);
}

}  // namespace

bool collidePlaneBox(const Pose& plane, const Vec3& half, const Pose& box, double margin,
                     Manifold& out) {
  const Vec3 n = plane.orientation * Vec3::UnitY();
  const Eigen::Matrix3d r = box.orientation.toRotationMatrix();
  // The plane is the reference surface; the incident points are the corners of the box face
  // most anti-parallel to it, which holds the deepest corner. Not all eight: a speculative
  // margin grows with speed, and once it passed a thin box's thickness (a plank 10 cm thick
  // sliding at 6 m/s) the far face's corners came in, and the reduction to four kept two of
  // them, which carry nothing, in place of two resting corners: the plank rode on one end and
  // sank (3.9 cm under Gauss-Seidel; 1.7 cm under the soft steps, which stopped it 18 % short).
  const Vec3 local_n = r.transpose() * n;
  int axis = 0;
  local_n.cwiseAbs().maxCoeff(&axis);
  const std::uint32_t face_bit = 1u << axis;
  const bool positive_face = local_n[axis] < 0.0;
  Vec3 points[4];
  double sep[4];
  std::uint32_t feature[4];
  int count = 0;
  for (std::uint32_t c = 0; c < 8; ++c) {
    if (((c & face_bit) != 0) != positive_face) continue;
    const Vec3 corner((c & 1) ? half.x() : -half.x(), (c & 2) ? half.y() : -half.y(),
                      (c & 4) ? half.z() : -half.z());
    points[count] = box.position + r * corner;
    sep[count] = n.dot(points[count] - plane.position);
    feature[count] = c;
    ++count;
  }
  out.normal = n;
  emit(points, sep, feature, count, n, margin, out);
  return out.count > 0;
}

bool collideBoxes(const Vec3& half_a, const Pose& a, const Vec3& half_b, const Pose& b,
                  double margin, Manifold& out) {
  const Eigen::Matrix3d ra = a.orientation.toRotationMatrix();
  const Eigen::Matrix3d rb = b.orientation.toRotationMatrix();
  const Vec3 d = b.position - a.position;
  constexpr double lowest = -std::numeric_limits<double>::infinity();
  double face_a = lowest, face_b = lowest, edge = lowest;
  int axis_a = 0, axis_b = 0, edge_i = 0, edge_j = 0;
  Vec3 edge_axis = Vec3::UnitY();
  for (int i = 0; i < 3; ++i) {
    const double s = separation(ra.col(i), d, ra, half_a, rb, half_b);
    if (s > margin) return false;
    if (s > face_a) face_a = s, axis_a = i;
  }
  for (int j = 0; j < 3; ++j) {
    const double s = separation(rb.col(j), d, ra, half_a, rb, half_b);
    if (s > margin) return false;
    if (s > face_b) face_b = s, axis_b = j;
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Vec3 c = ra.col(i).cross(rb.col(j));
      const double len = c.norm();
      // Parallel edges: the face axes already cover this direction.
      if (len < 1e-6) continue;
      c /= len;
      const double s = separation(c, d, ra, half_a, rb, half_b);
      if (s > margin) return false;
      if (s > edge) edge = s, edge_i = i, edge_j = j, edge_axis = c;
    }
  }
  // Tolerances keep the choice of feature steady from step to step (as in Box2D): a face
  // contact is preferred unless an edge axis separates clearly more.
  constexpr double kTolerance = 0.005;
  const double face = std::max(face_a, face_b);
  if (edge > face + kTolerance) {
    const Vec3 n = edge_axis.dot(d) >= 0.0 ? edge_axis : Vec3(-edge_axis);
    Vec3 pa = a.position, pb = b.position;
    for (int k = 0; k < 3; ++k) {
      if (k != edge_i) pa += signOf(n.dot(ra.col(k))) * half_a[k] * ra.col(k);
      if (k != edge_j) pb -= signOf(n.dot(rb.col(k))) * half_b[k] * rb.col(k);
    }
    // Closest points of the two supporting edges.
    const Vec3 ua = ra.col(edge_i), ub = rb.col(edge_j), w = pa - pb;
    const double bb = ua.dot(ub), den = 1.0 - bb * bb;
    double sa = den > 1e-12 ? (bb * ub.dot(w) - ua.dot(w)) / den : 0.0;
    sa = std::clamp(sa, -half_a[edge_i], half_a[edge_i]);
    double sb = std::clamp(ub.dot(pa + sa * ua - pb), -half_b[edge_j], half_b[edge_j]);
    const Vec3 qa = pa + sa * ua, qb = pb + sb * ub;
    out.normal = n;
    out.count = 0;
    out.add(0.5 * (qa + qb), -edge, (1u << 16) + 3u * edge_i + edge_j);
    return true;
  }
  if (face_b > face_a + kTolerance) {
    faceContact(rb, b.position, half_b, axis_b, ra, a.position, half_a, true, margin, out);
  } else {
    faceContact(ra, a.position, half_a, axis_a, rb, b.position, half_b, false, margin, out);
  }
  return out.count > 0;
}

}  // namespace zonesim::physics
