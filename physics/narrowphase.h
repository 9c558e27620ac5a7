#pragma once
// Narrowphase dispatch: one switch over the pair's shape types, no virtual calls.

#include "physics/contact.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Contacts between shape A at pose a and shape B at pose b when their gap is at most margin;
/// the manifold normal points from A to B. Plane-plane pairs never collide. Compounds are
/// collided piece by piece (forEachPiece in physics/compound.h): given one, this returns false.
bool collideShapes(const Shape& sa, const Pose& a, const Shape& sb, const Pose& b, double margin,
                   Manifold& out);

}  // namespace zonesim::physics
