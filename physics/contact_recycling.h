#pragma once
// Contact recycling (after Box2D v3.1): a pair whose bodies barely moved relative to each other
// since its manifold was computed keeps that manifold instead of running the narrowphase again.
// Each point rides along with both bodies, and its depth changes by how far the two copies of
// the point moved apart along the kept normal (as the soft step's sub-steps already update
// separations). The test is the largest distance any point of one body can have moved in the
// other's frame, from the two poses and the body's bounding radius, so it is exact for any
// shape, and a pair is recycled only while it certainly stays within the contact margin: the
// set of touching pairs, and so every contact's begin and end, is what the narrowphase finds.

#include <array>
#include <cstdint>

#include "common/math.h"
#include "physics/contact.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Where a manifold came from: both bodies' poses when the narrowphase ran, and each point's
/// position and depth then. Kept for the contact, so later steps can carry the points along.
struct ManifoldOrigin {
  Pose a, b;
  std::array<Vec3, 4> point{};
  std::array<double, 4> depth{};
};

/// BodyContact::origin of a contact without one (recycling off, or not a recycled shape).
constexpr std::uint32_t kNoOrigin = 0xffffffffu;

/// The farthest any point of the shape lies from its body's origin (m); infinite for a plane.
double boundingRadius(const Shape& shape);

/// A bound (m) on how far the shapes' distance, or depth, has changed since the poses `then`:
/// how far any point of one body has moved in the other's frame, |change of its origin there|
/// + its bounding radius x the chord of the relative rotation. The bound for b is returned when
/// it is below `enough`, else the smaller of the two.
double relativeMotionBound(const ManifoldOrigin& then, const Pose& a, const Pose& b,
                           double radius_a, double radius_b, double enough);

/// True when neither body turned more than `max_turn_cos` (the cosine of the largest angle)
/// since `then`: the kept normal is fixed in the world, so a pair that turned as a whole needs
/// a new one.
bool turnedLittle(const ManifoldOrigin& then, const Pose& a, const Pose& b, double max_turn_cos);

/// The manifold `then` made, carried to poses a and b: each point moved with both bodies, its
/// position midway between the two copies and its depth less their separation along the normal.
void carryManifold(const ManifoldOrigin& then, const Vec3& normal, int count, const Pose& a,
                   const Pose& b, Manifold& out);

/// Puts a carried manifold's points deepest first, each with its origin and impulses (stable
/// among equal depths), as physics/manifold_order.h orders fresh ones. Kept in their first
/// order while the box rocked, they let a 20-box column walk 3.4 cm in 60 s under the wide
/// soft step (20 iterations, one relax pass, recycling at 0.01 m), against 84 um without
/// recycling (ContactRecycling.ARecycledColumnStandsAsStillAsAComputedOne).
void sortDeepestFirst(Manifold& m, ManifoldOrigin& origin,
                      std::array<std::array<double, 3>, 4>& impulse);

/// Records the poses and points of a manifold just computed.
ManifoldOrigin originOf(const Manifold& m, const Pose& a, const Pose& b);

}  // namespace zonesim::physics
