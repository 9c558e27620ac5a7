#pragma once
// A plain 2D vector for the crowd library: the ground plane of the world (x, z in the zone's
// Vec3 map to x, y here). No Eigen, so the header stays cheap to include and the arrays of
// agents are plain contiguous doubles that the zone can fill without conversion overhead.

#include <cmath>

namespace zonesim::crowd {

/// Position, velocity or force on the ground plane.
struct Vec2 {
  double x = 0.0;  ///< world x
  double y = 0.0;  ///< world z of the zone (the plane's second axis)

  /// Component-wise sum.
  friend Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
  /// Component-wise difference.
  friend Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
  /// Scaling.
  friend Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
  /// Scaling.
  friend Vec2 operator*(double s, Vec2 a) { return {a.x * s, a.y * s}; }
  /// Accumulation.
  Vec2& operator+=(Vec2 b) {
    x += b.x;
    y += b.y;
    return *this;
  }
  /// Exact equality (used by the determinism tests).
  friend bool operator==(const Vec2&, const Vec2&) = default;
};

/// Dot product.
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
/// Squared length.
inline double lengthSq(Vec2 a) {
  return dot(a, a);
}
/// Length.
inline double length(Vec2 a) {
  return std::sqrt(lengthSq(a));
}

/// `v` shortened to at most `maxLen` (unchanged when already shorter).
inline Vec2 clampLength(Vec2 v, double maxLen) {
  double l2 = lengthSq(v);
  if (l2 <= maxLen * maxLen) return v;
  return v * (maxLen / std::sqrt(l2));
}

/// `v` scaled to length `len`, or zero when `v` is (nearly) zero: no direction to keep.
inline Vec2 withLength(Vec2 v, double len) {
  double l2 = lengthSq(v);
  if (l2 < 1e-24) return {};
  return v * (len / std::sqrt(l2));
}

}  // namespace zonesim::crowd
