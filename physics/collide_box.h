#pragma once
// Box against plane and box against box (separating axis test with face clipping).

#include "physics/contact.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Plane A against box B: the box corners within margin of the plane, at most four.
bool collidePlaneBox(const Pose& plane, const Vec3& half, const Pose& box, double margin,
                     Manifold& out);

/// Box A against box B by the separating axis test over the 15 axes (3 + 3 faces, 9 edge
/// pairs). Face contacts clip the incident face against the reference face's sides
/// (Sutherland-Hodgman) for up to four points; edge contacts give one point.
bool collideBoxes(const Vec3& half_a, const Pose& a, const Vec3& half_b, const Pose& b,
                  double margin, Manifold& out);

}  // namespace zonesim::physics
