#include "physics/clip.h"

namespace zonesim::physics {

int clipPolygon(const ClipVertex* in, int count, const Vec3& n, double offset,
                std::uint32_t plane_id, ClipVertex* out) {
  // Points up to a micrometre outside count as inside: the incident face of an equal-sized,
  // aligned box lies on the side planes, and round-off would otherwise cut extra points in the
  // middle of its edges, making the manifold lopsided (a stack then walks sideways).
  constexpr double kTolerance = 1e-6;
  int written = 0;
  for (int i = 0; i < count; ++i) {
    const ClipVertex& a = in[i];
    const ClipVertex& b = in[(i + 1) % count];
    const double da = n.dot(a.p) - offset - kTolerance;
    const double db = n.dot(b.p) - offset - kTolerance;
    if (da <= 0.0) out[written++] = a;
    if ((da <= 0.0) != (db <= 0.0)) {
      const double t = da / (da - db);
      // Feature of a crossing: which edge (its start vertex's feature) met which side plane.
      out[written++] = ClipVertex{a.p + t * (b.p - a.p), 16u + (a.feature << 3) + plane_id};
    }
  }
  return written;
}

void reduceToFour(const Vec3* points, const double* depth, int count, const Vec3& n, int keep[4]) {
  int first = 0;
  for (int i = 1; i < count; ++i) {
    if (depth[i] > depth[first]) first = i;
  }
  int second = first;
  double best = -1.0;
  for (int i = 0; i < count; ++i) {
    const double d = (points[i] - points[first]).squaredNorm();
    if (d > best) best = d, second = i;
  }
  // Third and fourth: largest triangle on either side of the first-second line.
  int third = first, fourth = first;
  double most = 0.0, least = 0.0;
  for (int i = 0; i < count; ++i) {
    const double area = n.dot((points[second] - points[first]).cross(points[i] - points[first]));
    if (area > most) most = area, third = i;
    if (area < least) least = area, fourth = i;
  }
  keep[0] = first;
  keep[1] = second;
  keep[2] = third;
  keep[3] = fourth;
}

}  // namespace zonesim::physics
