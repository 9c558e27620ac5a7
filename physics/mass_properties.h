#pragma once
// Mass and principal inertia of uniform-density shapes, about the centre of mass.

#include "common/math.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Mass and the diagonal of the inertia tensor in the shape's principal (local) frame.
struct MassProperties {
  double mass = 0.0;
  Vec3 inertia = Vec3::Zero();
};

/// Mass properties of a shape of uniform density; planes have none (zero mass).
MassProperties computeMassProperties(const Shape& shape, double density);

}  // namespace zonesim::physics
