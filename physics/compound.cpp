#include "physics/compound.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "physics/mass_properties.h"

namespace zonesim::physics {

namespace {

void checkPart(const ShapePart& p, std::size_t k) {
  const std::string where = "compound part " + std::to_string(k) + ": ";
  const Shape& s = p.shape;
  switch (s.type) {
    case ShapeType::Plane:
      throw std::invalid_argument(where + "a plane is unbounded and cannot be part of a body");
    case ShapeType::Compound:
      throw std::invalid_argument(where + "a compound cannot hold another compound");
    case ShapeType::Box:
      if (!(s.half_extents.minCoeff() > 0.0))
        throw std::invalid_argument(where + "every half extent of a box must be > 0");
      break;
    case ShapeType::Capsule:
      if (!(s.half_height >= 0.0))
        throw std::invalid_argument(where + "a capsule's half height must be >= 0");
      [[fallthrough]];
    case ShapeType::Sphere:
      if (!(s.radius > 0.0)) throw std::invalid_argument(where + "the radius must be > 0");
      break;
  }
  if (!p.position.allFinite()) throw std::invalid_argument(where + "position is not finite");
  const double norm = p.orientation.norm();
  if (!std::isfinite(norm) || norm == 0.0)
    throw std::invalid_argument(where + "orientation is not a rotation");
}

}  // namespace

Shape makeCompound(std::vector<ShapePart> parts) {
  if (parts.empty()) throw std::invalid_argument("a compound needs at least one part");
  // Contacts name their piece in 16 bits (BodyContact::piece_a, piece_b).
  if (parts.size() > 65536)
    throw std::invalid_argument("a compound has at most 65536 parts, not " +
                                std::to_string(parts.size()));
  for (std::size_t k = 0; k < parts.size(); ++k) {
    checkPart(parts[k], k);
    parts[k].orientation.normalize();
  }
  Shape s;
  s.type = ShapeType::Compound;
  s.parts = std::make_shared<const std::vector<ShapePart>>(std::move(parts));
  return s;
}

CentredCompound centreCompound(std::vector<ShapePart> parts) {
  const Shape placed = makeCompound(std::move(parts));
  // Uniform density: the centre does not depend on its value.
  const Vec3 centre = computeMassProperties(placed, 1.0).centre;
  std::vector<ShapePart> moved = *placed.parts;
  for (ShapePart& p : moved) p.position -= centre;
  return CentredCompound{makeCompound(std::move(moved)), centre};
}

}  // namespace zonesim::physics
