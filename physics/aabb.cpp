#include "physics/aabb.h"

#include <limits>

namespace zonesim::physics {

Aabb shapeBounds(const Shape& shape, const Vec3& position, const Quat& orientation) {
  Vec3 half = Vec3::Zero();
  switch (shape.type) {
    case ShapeType::Sphere:
      half = Vec3::Constant(shape.radius);
      break;
    case ShapeType::Box:
      // |R| h: the half extent of a rotated box along each world axis.
      half = orientation.toRotationMatrix().cwiseAbs() * shape.half_extents;
      break;
    case ShapeType::Capsule:
      half =
          (orientation * Vec3(0, shape.half_height, 0)).cwiseAbs() + Vec3::Constant(shape.radius);
      break;
    case ShapeType::Plane:
      half = Vec3::Constant(std::numeric_limits<double>::infinity());
      break;
    case ShapeType::Compound: {
      Aabb all{Vec3::Constant(std::numeric_limits<double>::infinity()),
               Vec3::Constant(-std::numeric_limits<double>::infinity())};
      for (const ShapePart& p : *shape.parts) {
        all = all.merged(
            shapeBounds(p.shape, position + orientation * p.position, orientation * p.orientation));
      }
      return all;
    }
  }
  return Aabb{position - half, position + half};
}

}  // namespace zonesim::physics
