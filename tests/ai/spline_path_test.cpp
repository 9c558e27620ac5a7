// Catmull-Rom following: through every control point, constant speed, arrival at the end.

#include "ai/spline_path.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ai/grid_search.h"

namespace zonesim::ai {
namespace {

TEST(SplinePath, PassesThroughEveryControlPoint) {
  std::vector<Vec2> pts{{0, 0}, {1, 0}, {2, 1}, {2, 3}, {5, 3}};
  SplinePath spline(pts);
  ASSERT_EQ(spline.segments(), 4);
  for (int i = 0; i < 5; ++i) {
    Vec2 p = spline.at(i);
    EXPECT_DOUBLE_EQ(p.x, pts[std::size_t(i)].x);
    EXPECT_DOUBLE_EQ(p.y, pts[std::size_t(i)].y);
  }
}

TEST(SplinePath, StraightLineIsStraightAndExact) {
  SplinePath spline({{0, 0}, {1, 0}, {2, 0}, {3, 0}});
  EXPECT_NEAR(spline.length(), 3.0, 1e-9);
  Vec2 p = spline.atDistance(1.7);
  EXPECT_NEAR(p.x, 1.7, 1e-6);
  EXPECT_NEAR(p.y, 0.0, 1e-12);
}

TEST(SplineFollower, MovesAtConstantSpeedAndArrives) {
  GridMap m(30, 30);
  for (int y = 0; y < 25; ++y) m.setPassable(15, y, false);
  GridSearch search(m);
  GridPath path;
  ASSERT_TRUE(search.findPath({2, 2}, {27, 3}, path));
  SplinePath spline(SplinePath::cellCentres(path));
  // Smoothing never adds more than a little to the length of the polyline through the cells.
  EXPECT_LE(spline.length(), path.length * 1.05);
  EXPECT_GE(spline.length(), octileDistance(Cell{2, 2}, Cell{27, 3}) * 0.9);

  const double speed = 4.0, dt = 0.05;
  SplineFollower follower(spline, speed);
  Vec2 prev = follower.position();
  int steps = 0;
  while (!follower.arrived() && steps < 100000) {
    Vec2 p = follower.advance(dt);
    double moved = std::hypot(p.x - prev.x, p.y - prev.y);
    // The arc-length table is piecewise linear, so steps match the speed to within a percent;
    // chords are shorter than arcs, but on a curve sampled this finely not by much.
    EXPECT_LE(moved, speed * dt * 1.01);
    if (!follower.arrived()) {
      EXPECT_GE(moved, speed * dt * 0.9);
    }
    // The agent never strays more than a cell from the cells of the path.
    int cx = int(std::floor(p.x)), cy = int(std::floor(p.y));
    EXPECT_TRUE(m.passable(cx, cy) || m.passable(int(std::floor(p.x + 0.5)), cy) ||
                m.passable(int(std::floor(p.x - 0.5)), cy))
        << p.x << "," << p.y;
    prev = p;
    ++steps;
  }
  EXPECT_TRUE(follower.arrived());
  EXPECT_NEAR(follower.position().x, 27.5, 1e-9);
  EXPECT_NEAR(follower.position().y, 3.5, 1e-9);
  EXPECT_NEAR(steps * speed * dt, spline.length(), speed * dt);
}

TEST(SplinePath, SinglePointStaysPut) {
  SplinePath spline({{4, 5}});
  SplineFollower follower(spline, 1.0);
  EXPECT_TRUE(follower.arrived());
  EXPECT_DOUBLE_EQ(follower.advance(1.0).x, 4.0);
}

}  // namespace
}  // namespace zonesim::ai
