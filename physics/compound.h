#pragma once
// Compound shapes: several spheres, boxes and capsules fixed to one body. A body turns about
// its origin, so a dynamic compound's origin must be its parts' centre of mass;
// centreCompound() arranges that.

#include <vector>

#include "physics/contact.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// A compound of the given parts, as placed. Throws std::invalid_argument naming the part when
/// there are no parts or more than 65536, a part is a plane or itself a compound, or a size is
/// not positive.
Shape makeCompound(std::vector<ShapePart> parts);

/// A compound with its parts moved so that their centre of mass (uniform density) is the
/// body origin, and where that centre was in the frame the parts were given in.
struct CentredCompound {
  Shape shape;
  Vec3 centre = Vec3::Zero();
};

/// makeCompound() with the parts moved to their centre of mass: a body meant to sit at pose
/// (p, q) in the parts' frame goes at position p + q * centre.
CentredCompound centreCompound(std::vector<ShapePart> parts);

/// Calls visit(index, shape, pose) for each convex piece of `shape` at `pose`: the parts of a
/// compound in order, or the shape itself as piece 0.
template <class Visit>
void forEachPiece(const Shape& shape, const Pose& pose, Visit&& visit) {
  if (shape.type != ShapeType::Compound) {
    visit(0u, shape, pose);
    return;
  }
  const std::vector<ShapePart>& parts = *shape.parts;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const ShapePart& p = parts[k];
    visit(static_cast<unsigned>(k), p.shape,
          Pose{pose.position + pose.orientation * p.position, pose.orientation * p.orientation});
  }
}

}  // namespace zonesim::physics
