#pragma once
// Sphere against sphere, plane and box. Each returns false when the gap exceeds margin; the
// manifold normal points from the first shape to the second.

#include "physics/contact.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Sphere A (centre a, radius ra) against sphere B.
bool collideSpheres(const Vec3& a, double ra, const Vec3& b, double rb, double margin,
                    Manifold& out);
/// Plane A (through its origin, normal local +y) against sphere B.
bool collidePlaneSphere(const Pose& plane, const Vec3& b, double rb, double margin, Manifold& out);
/// Box A against sphere B.
bool collideBoxSphere(const Vec3& half, const Pose& box, const Vec3& b, double rb, double margin,
                      Manifold& out);

}  // namespace zonesim::physics
