#include "physics/narrowphase.h"

#include "physics/collide_box.h"
#include "physics/collide_capsule.h"
#include "physics/collide_sphere.h"

namespace zonesim::physics {

namespace {

/// The order in which the pair functions take their arguments.
int rank(ShapeType t) {
  switch (t) {
    case ShapeType::Plane:
      return 0;
    case ShapeType::Box:
      return 1;
    case ShapeType::Capsule:
      return 2;
    case ShapeType::Sphere:
      return 3;
    case ShapeType::Compound:
      return 4;
  }
  return 4;
}

/// Pairs in rank order: rank(sa.type) <= rank(sb.type).
bool collideOrdered(const Shape& sa, const Pose& a, const Shape& sb, const Pose& b, double margin,
                    Manifold& out) {
  switch (sa.type) {
    case ShapeType::Plane:
      switch (sb.type) {
        case ShapeType::Plane:
          return false;
        case ShapeType::Box:
          return collidePlaneBox(a, sb.half_extents, b, margin, out);
        case ShapeType::Capsule:
          return collidePlaneCapsule(a, sb, b, margin, out);
        case ShapeType::Sphere:
          return collidePlaneSphere(a, b.position, sb.radius, margin, out);
        case ShapeType::Compound:
          return false;
      }
      return false;
    case ShapeType::Box:
      switch (sb.type) {
        case ShapeType::Box:
          return collideBoxes(sa.half_extents, a, sb.half_extents, b, margin, out);
        case ShapeType::Capsule:
          return collideBoxCapsule(sa.half_extents, a, sb, b, margin, out);
        case ShapeType::Sphere:
          return collideBoxSphere(sa.half_extents, a, b.position, sb.radius, margin, out);
        case ShapeType::Plane:
        case ShapeType::Compound:
          return false;
      }
      return false;
    case ShapeType::Capsule:
      if (sb.type == ShapeType::Capsule) return collideCapsules(sa, a, sb, b, margin, out);
      if (sb.type == ShapeType::Sphere) {
        return collideCapsuleSphere(sa, a, b.position, sb.radius, margin, out);
      }
      return false;
    case ShapeType::Sphere:
      if (sb.type != ShapeType::Sphere) return false;
      return collideSpheres(a.position, sa.radius, b.position, sb.radius, margin, out);
    case ShapeType::Compound:
      return false;
  }
  return false;
}

}  // namespace

bool collideShapes(const Shape& sa, const Pose& a, const Shape& sb, const Pose& b, double margin,
                   Manifold& out) {
  if (rank(sa.type) <= rank(sb.type)) return collideOrdered(sa, a, sb, b, margin, out);
  if (!collideOrdered(sb, b, sa, a, margin, out)) return false;
  out.normal = -out.normal;
  return true;
}

}  // namespace zonesim::physics
