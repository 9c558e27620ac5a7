#include "physics/narrowphase.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace zonesim::physics {
namespace {

constexpr double kEps = 1e-9;

Pose at(const Vec3& p, const Quat& q = Quat::Identity()) {
  return Pose{p, q};
}

Quat about(const Vec3& axis, double degrees) {
  return Quat(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis.normalized()));
}

void expectVec(const Vec3& got, const Vec3& want, double tol = kEps) {
  EXPECT_NEAR((got - want).norm(), 0.0, tol) << got.transpose() << " vs " << want.transpose();
}

TEST(Narrowphase, SphereSphere) {
  Manifold m;
  ASSERT_TRUE(collideShapes(Shape::sphere(1), at(Vec3::Zero()), Shape::sphere(1),
                            at(Vec3(1.5, 0, 0)), 0.0, m));
  ASSERT_EQ(m.count, 1);
  expectVec(m.normal, Vec3::UnitX());
  EXPECT_NEAR(m.points[0].depth, 0.5, kEps);
  expectVec(m.points[0].position, Vec3(0.75, 0, 0));
  EXPECT_FALSE(collideShapes(Shape::sphere(1), at(Vec3::Zero()), Shape::sphere(1),
                             at(Vec3(2.1, 0, 0)), 0.05, m));
  // Within the margin: a speculative contact with negative depth (the gap).
  ASSERT_TRUE(collideShapes(Shape::sphere(1), at(Vec3::Zero()), Shape::sphere(1),
                            at(Vec3(2.1, 0, 0)), 0.2, m));
  EXPECT_NEAR(m.points[0].depth, -0.1, kEps);
}

TEST(Narrowphase, SpherePlaneOnASlope) {
  Manifold m;
  const Quat tilt = about(Vec3::UnitZ(), 30);
  const Vec3 n = tilt * Vec3::UnitY();
  ASSERT_TRUE(collideShapes(Shape::plane(), at(Vec3(0, 1, 0), tilt), Shape::sphere(1),
                            at(Vec3(0, 1, 0) + 0.8 * n), 0.0, m));
  expectVec(m.normal, n);
  EXPECT_NEAR(m.points[0].depth, 0.2, kEps);
  expectVec(m.points[0].position, Vec3(0, 1, 0) - 0.1 * n);
}

TEST(Narrowphase, SphereBoxFaceAndCorner) {
  Manifold m;
  const Shape box = Shape::box(Vec3(1, 1, 1));
  ASSERT_TRUE(collideShapes(box, at(Vec3::Zero()), Shape::sphere(1), at(Vec3(0, 1.5, 0)), 0, m));
  expectVec(m.normal, Vec3::UnitY());
  EXPECT_NEAR(m.points[0].depth, 0.5, kEps);
  expectVec(m.points[0].position, Vec3(0, 0.75, 0));
  ASSERT_TRUE(collideShapes(box, at(Vec3::Zero()), Shape::sphere(1), at(Vec3(1.5, 1.5, 0)), 0, m));
  expectVec(m.normal, Vec3(1, 1, 0).normalized());
  EXPECT_NEAR(m.points[0].depth, 1.0 - std::sqrt(0.5), kEps);
  // Centre inside the box: pushed out through the nearest face (+x here).
  ASSERT_TRUE(
      collideShapes(box, at(Vec3::Zero()), Shape::sphere(0.2), at(Vec3(0.9, 0.1, 0)), 0, m));
  expectVec(m.normal, Vec3::UnitX());
  EXPECT_NEAR(m.points[0].depth, 0.3, kEps);
}

TEST(Narrowphase, BoxRestingOnPlaneGivesFourCorners) {
  Manifold m;
  ASSERT_TRUE(collideShapes(Shape::plane(), at(Vec3::Zero()), Shape::box(Vec3(1, 0.5, 2)),
                            at(Vec3(0, 0.4, 0)), 0.0, m));
  ASSERT_EQ(m.count, 4);
  expectVec(m.normal, Vec3::UnitY());
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(m.points[i].depth, 0.1, kEps);
    EXPECT_NEAR(m.points[i].position.y(), -0.05, kEps);
    EXPECT_NEAR(std::abs(m.points[i].position.x()), 1.0, kEps);
    EXPECT_NEAR(std::abs(m.points[i].position.z()), 2.0, kEps);
  }
  // On an edge (45 degrees about z): the two corners of the lowest edge.
  ASSERT_TRUE(collideShapes(Shape::plane(), at(Vec3::Zero()), Shape::box(Vec3(1, 1, 1)),
                            at(Vec3(0, std::sqrt(2.0) - 0.1, 0), about(Vec3::UnitZ(), 45)), 0.0,
                            m));
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(m.points[i].depth, 0.1, kEps);
}

// A speculative margin wider than a thin box (a plank sliding fast gets one) must not let its
// far face in: the manifold is the near face's four corners, all touching.
TEST(Narrowphase, ThinBoxWithinAWideMarginGivesItsNearFaceOnly) {
  Manifold m;
  ASSERT_TRUE(collideShapes(Shape::plane(), at(Vec3::Zero()), Shape::box(Vec3(1, 0.05, 0.5)),
                            at(Vec3(0, 0.05, 0), about(Vec3::UnitX(), 0.1)), 0.2, m));
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_LT(std::abs(m.points[i].depth), 1e-3) << i;
    EXPECT_NEAR(std::abs(m.points[i].position.x()), 1.0, 1e-3) << i;
  }
}

TEST(Narrowphase, BoxBoxFaceContactClipsToTheOverlap) {
  Manifold m;
  const Shape big = Shape::box(Vec3(1, 1, 1));
  ASSERT_TRUE(collideShapes(big, at(Vec3::Zero()), Shape::box(Vec3(0.5, 0.5, 0.5)),
                            at(Vec3(0.3, 1.4, 0.2)), 0.0, m));
  ASSERT_EQ(m.count, 4);
  expectVec(m.normal, Vec3::UnitY());
  for (int i = 0; i < 4; ++i) {
    const Vec3& p = m.points[i].position;
    EXPECT_NEAR(m.points[i].depth, 0.1, kEps);
    EXPECT_NEAR(p.y(), 0.95, kEps);
    EXPECT_NEAR(std::abs(p.x() - 0.3), 0.5, kEps);
    EXPECT_NEAR(std::abs(p.z() - 0.2), 0.5, kEps);
  }
  // Overhanging: the incident face is clipped to the reference face's sides (x <= 1).
  ASSERT_TRUE(collideShapes(big, at(Vec3::Zero()), big, at(Vec3(1.5, 1.9, 0)), 0.0, m));
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < 4; ++i) {
    const double x = m.points[i].position.x();
    // Clipping keeps points up to a micrometre outside the side planes (see clip.cpp).
    EXPECT_TRUE(std::abs(x - 0.5) < kEps || std::abs(x - 1.0) < 2e-6) << x;
    EXPECT_NEAR(m.points[i].depth, 0.1, kEps);
  }
}

TEST(Narrowphase, BoxBoxTwistedFaceReducesEightPointsToFour) {
  Manifold m;
  const Shape cube = Shape::box(Vec3(1, 1, 1));
  ASSERT_TRUE(collideShapes(cube, at(Vec3::Zero()), cube,
                            at(Vec3(0, 1.9, 0), about(Vec3::UnitY(), 45)), 0.0, m));
  ASSERT_EQ(m.count, 4);
  expectVec(m.normal, Vec3::UnitY());
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[i].depth, 0.1, kEps);
}

TEST(Narrowphase, BoxBoxEdgeEdge) {
  // A: an edge along z on top at y = sqrt(2). B: an edge along x at its bottom. They cross at
  // the origin's vertical, overlapping by 0.1.
  Manifold m;
  const Shape cube = Shape::box(Vec3(1, 1, 1));
  const double r2 = std::sqrt(2.0);
  ASSERT_TRUE(collideShapes(cube, at(Vec3::Zero(), about(Vec3::UnitZ(), 45)), cube,
                            at(Vec3(0, 2 * r2 - 0.1, 0), about(Vec3::UnitX(), 45)), 0.0, m));
  ASSERT_EQ(m.count, 1);
  expectVec(m.normal, Vec3::UnitY(), 1e-9);
  EXPECT_NEAR(m.points[0].depth, 0.1, kEps);
  expectVec(m.points[0].position, Vec3(0, r2 - 0.05, 0));
  EXPECT_FALSE(collideShapes(cube, at(Vec3::Zero(), about(Vec3::UnitZ(), 45)), cube,
                             at(Vec3(0, 2 * r2 + 0.1, 0), about(Vec3::UnitX(), 45)), 0.0, m));
}

TEST(Narrowphase, CapsuleAgainstPlaneSphereCapsuleAndBox) {
  Manifold m;
  const Shape cap = Shape::capsule(0.5, 1.0);
  const Quat lying = about(Vec3::UnitZ(), 90);  // Segment along x.
  ASSERT_TRUE(
      collideShapes(Shape::plane(), at(Vec3::Zero()), cap, at(Vec3(0, 0.4, 0), lying), 0.0, m));
  ASSERT_EQ(m.count, 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(m.points[i].depth, 0.1, kEps);
    EXPECT_NEAR(std::abs(m.points[i].position.x()), 1.0, kEps);
  }
  ASSERT_TRUE(collideShapes(cap, at(Vec3::Zero()), Shape::sphere(1), at(Vec3(1.2, 0.5, 0)), 0, m));
  expectVec(m.normal, Vec3::UnitX());
  EXPECT_NEAR(m.points[0].depth, 0.3, kEps);
  // Crossed capsules: one point between the surfaces.
  ASSERT_TRUE(collideShapes(cap, at(Vec3::Zero(), lying), cap,
                            at(Vec3(0, 0.9, 0), about(Vec3::UnitX(), 90)), 0.0, m));
  ASSERT_EQ(m.count, 1);
  expectVec(m.points[0].position, Vec3(0, 0.45, 0));
  // Parallel capsules side by side: two points.
  ASSERT_TRUE(
      collideShapes(cap, at(Vec3::Zero(), lying), cap, at(Vec3(0.5, 0.9, 0), lying), 0.0, m));
  EXPECT_EQ(m.count, 2);
  // Lying on a box top: both ends and the closest point, all at depth 0.1.
  ASSERT_TRUE(collideShapes(Shape::box(Vec3(2, 1, 2)), at(Vec3::Zero()), cap,
                            at(Vec3(0, 1.4, 0), lying), 0.0, m));
  expectVec(m.normal, Vec3::UnitY());
  ASSERT_GE(m.count, 2);
  for (int i = 0; i < m.count; ++i) EXPECT_NEAR(m.points[i].depth, 0.1, kEps);
}

TEST(Narrowphase, SwappingTheShapesFlipsOnlyTheNormal) {
  const Shape shapes[] = {Shape::sphere(0.7), Shape::box(Vec3(0.6, 0.4, 0.5)),
                          Shape::capsule(0.3, 0.5)};
  const Pose pa = at(Vec3(0.1, 0.2, -0.1), about(Vec3(1, 2, 3), 20));
  const Pose pb = at(Vec3(0.3, 0.9, 0.2), about(Vec3(-2, 1, 1), 35));
  int hits = 0;
  for (const Shape& a : shapes) {
    for (const Shape& b : shapes) {
      Manifold ab, ba;
      const bool hit = collideShapes(a, pa, b, pb, 0.0, ab);
      ASSERT_EQ(hit, collideShapes(b, pb, a, pa, 0.0, ba));
      if (!hit) continue;
      ++hits;
      // The normal points from the first shape to the second: towards B's centre here.
      EXPECT_GT(ab.normal.dot(pb.position - pa.position), 0.0);
      if (a.type == b.type) continue;  // Same-type pairs may pick another reference face.
      expectVec(ab.normal, -ba.normal, 1e-9);
      ASSERT_EQ(ab.count, ba.count);
      for (int i = 0; i < ab.count; ++i) EXPECT_NEAR(ab.points[i].depth, ba.points[i].depth, 1e-9);
    }
  }
  EXPECT_EQ(hits, 9);
}

}  // namespace
}  // namespace zonesim::physics
