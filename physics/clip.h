#pragma once
// Polygon clipping and contact reduction for face contacts.

#include <cstdint>

#include "common/math.h"

namespace zonesim::physics {

/// A polygon vertex carrying the feature id it came from.
struct ClipVertex {
  Vec3 p = Vec3::Zero();
  std::uint32_t feature = 0;
};

/// Sutherland-Hodgman: keeps the part of polygon in (count vertices) where n.p <= offset,
/// writing at most count + 1 vertices to out; returns the new count. New vertices get feature
/// ids from the edge and plane they come from (plane_id < 8).
int clipPolygon(const ClipVertex* in, int count, const Vec3& n, double offset,
                std::uint32_t plane_id, ClipVertex* out);

/// Picks 4 of count candidate points: the deepest, then those spanning the largest area around
/// it (normal n). Returns the chosen indices in keep.
void reduceToFour(const Vec3* points, const double* depth, int count, const Vec3& n, int keep[4]);

}  // namespace zonesim::physics
