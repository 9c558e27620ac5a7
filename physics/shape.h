#pragma once
// Collision shapes as small PODs: the narrowphase dispatches on the type with a switch, never
// through a virtual call, so bodies stay in dense arrays.

#include <cstdint>
#include <memory>
#include <vector>

#include "common/math.h"

namespace zonesim::physics {

/// The kinds of collision shape; planes are static half-spaces with local normal +y, and a
/// compound is several spheres, boxes and capsules fixed to one body (physics/compound.h).
enum class ShapeType : std::uint8_t { Sphere, Box, Capsule, Plane, Compound };

struct ShapePart;

/// One collision shape in its body's local frame (capsules lie along local y).
struct Shape {
  ShapeType type = ShapeType::Sphere;
  Vec3 half_extents = Vec3::Zero();  ///< Box half sizes.
  double radius = 0.0;               ///< Sphere and capsule radius.
  double half_height = 0.0;          ///< Capsule: half length of the inner segment.
  /// Compound: its parts in the body frame, shared and never changed, so that copying a shape
  /// stays cheap; null for every other type.
  std::shared_ptr<const std::vector<ShapePart>> parts;

  /// A sphere of radius r.
  static Shape sphere(double r) { return Shape{ShapeType::Sphere, Vec3::Zero(), r, 0.0, nullptr}; }
  /// A box with the given half sizes.
  static Shape box(const Vec3& half) { return Shape{ShapeType::Box, half, 0.0, 0.0, nullptr}; }
  /// A capsule: a segment of half length h along local y, swept by radius r.
  static Shape capsule(double r, double h) {
    return Shape{ShapeType::Capsule, Vec3::Zero(), r, h, nullptr};
  }
  /// A half-space whose surface passes through the body origin with normal along local +y.
  static Shape plane() { return Shape{ShapeType::Plane, Vec3::Zero(), 0.0, 0.0, nullptr}; }
};

/// One shape of a compound, placed in the compound body's frame.
struct ShapePart {
  Shape shape;
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
};

/// The lever arm of rolling resistance: the radius a sphere or capsule rolls on; 0 for shapes
/// that do not roll (boxes tip instead, planes never move).
inline double rollingRadius(const Shape& s) {
  return s.type == ShapeType::Sphere || s.type == ShapeType::Capsule ? s.radius : 0.0;
}

}  // namespace zonesim::physics
