#pragma once
// Mass and inertia of uniform-density shapes, about the centre of mass.

#include "common/math.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Mass, centre of mass and the inertia tensor about that centre, in the shape's frame. The
/// tensor of a sphere, box or capsule is diagonal; a compound's generally is not.
struct MassProperties {
  double mass = 0.0;
  Vec3 centre = Vec3::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
};

/// Mass properties of a shape of uniform density; planes have none (zero mass).
MassProperties computeMassProperties(const Shape& shape, double density);

}  // namespace zonesim::physics
