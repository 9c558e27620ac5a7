#include "ai/spline_path.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace zonesim::ai {

namespace {

double distance(Vec2 a, Vec2 b) {
  return std::hypot(b.x - a.x, b.y - a.y);
}

Vec2 lerp(Vec2 a, Vec2 b, double ta, double tb, double t) {
  double span = tb - ta;
  if (span <= 0) return a;
  double wa = (tb - t) / span, wb = (t - ta) / span;
  return Vec2{wa * a.x + wb * b.x, wa * a.y + wb * b.y};
}

// Barry-Goldman pyramid for a centripetal (alpha = 0.5) Catmull-Rom segment from p1 to p2.
Vec2 centripetal(Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3, double u) {
  auto knot = [](Vec2 a, Vec2 b) { return std::max(std::sqrt(distance(a, b)), 1e-9); };
  double t0 = 0, t1 = t0 + knot(p0, p1), t2 = t1 + knot(p1, p2), t3 = t2 + knot(p2, p3);
  double t = t1 + u * (t2 - t1);
  Vec2 a1 = lerp(p0, p1, t0, t1, t), a2 = lerp(p1, p2, t1, t2, t), a3 = lerp(p2, p3, t2, t3, t);
  Vec2 b1 = lerp(a1, a2, t0, t2, t), b2 = lerp(a2, a3, t1, t3, t);
  return lerp(b1, b2, t1, t2, t);
}

}  // namespace

SplinePath::SplinePath(std::vector<Vec2> points, int samplesPerSegment, Curve curve)
    : points_(std::move(points)),
      // A polyline's arc length is exact with one sample a segment.
      samples_(curve == Curve::Polyline ? 1 : std::max(samplesPerSegment, 1)),
      curve_(curve) {
  assert(!points_.empty());
  cumulative_.push_back(0.0);
  Vec2 prev = points_.front();
  for (int seg = 0; seg < segments(); ++seg) {
    for (int i = 1; i <= samples_; ++i) {
      Vec2 p = at(seg + double(i) / samples_);
      cumulative_.push_back(cumulative_.back() + distance(prev, p));
      prev = p;
    }
  }
}

std::vector<Vec2> SplinePath::cellCentres(const GridPath& path) {
  std::vector<Vec2> out;
  out.reserve(path.cells.size());
  for (Cell c : path.cells) out.push_back(Vec2{c.x + 0.5, c.y + 0.5});
  return out;
}

Vec2 SplinePath::at(double t) const {
  const int n = segments();
  if (n <= 0) return points_.front();
  t = std::clamp(t, 0.0, double(n));
  int seg = std::min(int(t), n - 1);
  double u = t - seg;
  // End segments mirror their neighbour to get a phantom control point.
  Vec2 p1 = points_[std::size_t(seg)], p2 = points_[std::size_t(seg) + 1];
  Vec2 p0 = seg > 0 ? points_[std::size_t(seg) - 1] : Vec2{2 * p1.x - p2.x, 2 * p1.y - p2.y};
  Vec2 p3 = seg + 2 <= n ? points_[std::size_t(seg) + 2] : Vec2{2 * p2.x - p1.x, 2 * p2.y - p1.y};
  if (u <= 0) return p1;
  if (u >= 1) return p2;
  if (curve_ == Curve::Polyline) return lerp(p1, p2, 0.0, 1.0, u);
  return centripetal(p0, p1, p2, p3, u);
}

Vec2 SplinePath::atDistance(double s) const {
  if (segments() <= 0) return points_.front();
  s = std::clamp(s, 0.0, length());
  auto it = std::upper_bound(cumulative_.begin(), cumulative_.end(), s);
  std::size_t hi = std::min(std::size_t(it - cumulative_.begin()), cumulative_.size() - 1);
  std::size_t lo = hi - 1;
  double span = cumulative_[hi] - cumulative_[lo];
  double frac = span > 0 ? (s - cumulative_[lo]) / span : 0.0;
  return at((double(lo) + frac) / samples_);
}

Vec2 SplineFollower::advance(double dt) {
  travelled_ = std::min(travelled_ + speed_ * dt, path_.length());
  return position();
}

}  // namespace zonesim::ai
