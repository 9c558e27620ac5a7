#pragma once
// Capsules (a segment swept by a radius) against spheres, planes, capsules and boxes.

#include "physics/contact.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Capsule A against sphere B.
bool collideCapsuleSphere(const Shape& capsule, const Pose& a, const Vec3& b, double rb,
                          double margin, Manifold& out);
/// Plane A against capsule B: one point per segment end within margin.
bool collidePlaneCapsule(const Pose& plane, const Shape& capsule, const Pose& b, double margin,
                         Manifold& out);
/// Capsule A against capsule B; nearly parallel overlapping segments give two points.
bool collideCapsules(const Shape& ca, const Pose& a, const Shape& cb, const Pose& b, double margin,
                     Manifold& out);
/// Box A against capsule B: the segment's ends and its point closest to the box, as spheres.
bool collideBoxCapsule(const Vec3& half, const Pose& box, const Shape& capsule, const Pose& b,
                       double margin, Manifold& out);

}  // namespace zonesim::physics
