#pragma once
// Axis-aligned bounding boxes and the bounds of each shape in a given pose.

#include <cstdint>

#include "common/math.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// An axis-aligned box [lo, hi].
struct Aabb {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();

  /// True when the two boxes overlap or touch.
  bool overlaps(const Aabb& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
  /// True when o lies entirely inside this box.
  bool contains(const Aabb& o) const {
    return (lo.array() <= o.lo.array()).all() && (o.hi.array() <= hi.array()).all();
  }
  /// The smallest box holding both.
  Aabb merged(const Aabb& o) const { return Aabb{lo.cwiseMin(o.lo), hi.cwiseMax(o.hi)}; }
  /// Surface area: the cost measure of the tree's insertion heuristic.
  double area() const {
    const Vec3 d = hi - lo;
    return 2.0 * (d.x() * d.y() + d.y() * d.z() + d.z() * d.x());
  }
  /// The box grown by margin on every side.
  Aabb expanded(double margin) const {
    return Aabb{lo - Vec3::Constant(margin), hi + Vec3::Constant(margin)};
  }
};

/// A candidate pair of proxies (first < second) from the broadphase.
struct ProxyPair {
  std::uint32_t first = 0;
  std::uint32_t second = 0;
  /// Pairs sort lexicographically so that every broadphase reports the same ordered set.
  friend bool operator<(const ProxyPair& a, const ProxyPair& b) {
    return a.first != b.first ? a.first < b.first : a.second < b.second;
  }
  friend bool operator==(const ProxyPair& a, const ProxyPair& b) = default;
};

/// World bounds of a bounded shape (sphere, box, capsule, compound) at a pose; planes are unbounded
/// and are handled outside the broadphase.
Aabb shapeBounds(const Shape& shape, const Vec3& position, const Quat& orientation);

}  // namespace zonesim::physics
