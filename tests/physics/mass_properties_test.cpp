#include "physics/mass_properties.h"

#include <gtest/gtest.h>

#include <numbers>

namespace zonesim::physics {
namespace {

TEST(MassProperties, SphereMatchesTextbook) {
  const MassProperties mp = computeMassProperties(Shape::sphere(0.5), 1000.0);
  const double mass = 1000.0 * 4.0 / 3.0 * std::numbers::pi * 0.125;
  EXPECT_NEAR(mp.mass, mass, 1e-9);
  EXPECT_NEAR(mp.inertia(0, 0), 0.4 * mass * 0.25, 1e-9);
}

TEST(MassProperties, CubeIsSixthOfMassTimesSideSquared) {
  const MassProperties mp = computeMassProperties(Shape::box(Vec3(1, 1, 1)), 1000.0);
  EXPECT_NEAR(mp.mass, 8000.0, 1e-9);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(mp.inertia(k, k), 8000.0 * 4.0 / 6.0, 1e-9);
}

TEST(MassProperties, CuboidAxesFollowTheOtherTwoSides) {
  const MassProperties mp = computeMassProperties(Shape::box(Vec3(0.5, 1.0, 1.5)), 2.0);
  const double m = 2.0 * 1.0 * 2.0 * 3.0;
  EXPECT_NEAR(mp.inertia(0, 0), m / 12.0 * (4.0 + 9.0), 1e-12);
  EXPECT_NEAR(mp.inertia(1, 1), m / 12.0 * (1.0 + 9.0), 1e-12);
  EXPECT_NEAR(mp.inertia(2, 2), m / 12.0 * (1.0 + 4.0), 1e-12);
}

TEST(MassProperties, CapsuleWithoutSegmentIsASphere) {
  const MassProperties c = computeMassProperties(Shape::capsule(0.3, 0.0), 700.0);
  const MassProperties s = computeMassProperties(Shape::sphere(0.3), 700.0);
  EXPECT_NEAR(c.mass, s.mass, 1e-12);
  EXPECT_NEAR((c.inertia - s.inertia).norm(), 0.0, 1e-12);
}

TEST(MassProperties, CapsuleMatchesNumericalIntegration) {
  // Midpoint-rule integration over a voxel grid of the capsule's bounding box.
  const double r = 0.4, h = 0.6, rho = 1.0;
  const int n = 120;
  const Vec3 lo(-r, -h - r, -r), size(2 * r, 2 * (h + r), 2 * r);
  double mass = 0.0, ixx = 0.0, iyy = 0.0;
  const double dv = size.prod() / (double(n) * n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Vec3 p =
            lo + Vec3((i + 0.5) / n * size.x(), (j + 0.5) / n * size.y(), (k + 0.5) / n * size.z());
        const double cy = std::clamp(p.y(), -h, h);
        if ((p - Vec3(0, cy, 0)).squaredNorm() > r * r) continue;
        mass += rho * dv;
        ixx += rho * dv * (p.y() * p.y() + p.z() * p.z());
        iyy += rho * dv * (p.x() * p.x() + p.z() * p.z());
      }
  const MassProperties mp = computeMassProperties(Shape::capsule(r, h), rho);
  EXPECT_NEAR(mp.mass / mass, 1.0, 2e-3);
  EXPECT_NEAR(mp.inertia(0, 0) / ixx, 1.0, 3e-3);
  EXPECT_NEAR(mp.inertia(1, 1) / iyy, 1.0, 3e-3);
}

}  // namespace
}  // namespace zonesim::physics
