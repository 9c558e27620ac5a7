// Navigation meshes: the polygons are convex, disjoint and cover exactly the cells left after
// erosion; erosion keeps the radius from every wall; paths never cross a blocked (or eroded)
// cell, are never shorter than the straight line nor much longer than the 8-connected optimum
// (Dijkstra on random maps, the listed optima on the Moving AI files), and report no path
// where the grid has none; bad input is refused with a message that says what is wrong.

#include "ai/navmesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "ai/funnel.h"
#include "ai/navmesh_search.h"
#include "ai/scenario.h"
#include "ai/segment_cells.h"
#include "tests/ai/reference_dijkstra.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

// Number of path segments that cross a cell off `open` (blocked or eroded) or off the map.
int crossingsOff(const std::vector<std::uint8_t>& open, int w, int h, const NavPath& path) {
  int bad = 0;
  for (std::size_t k = 1; k < path.points.size(); ++k) {
    forEachCellCrossed(path.points[k - 1], path.points[k], [&](Cell c) {
      if (c.x < 0 || c.y < 0 || c.x >= w || c.y >= h || !open[std::size_t(c.y * w + c.x)]) ++bad;
    });
  }
  return bad;
}

std::string message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(NavMeshTest, PolygonsAreConvexDisjointAndCoverExactlyTheErodedCells) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    for (double radius : {0.0, 0.3, 0.8, 1.6}) {
      GridMap m = test::randomMap(40, 30, 0.04 * double(seed % 6), seed);
      NavMesh mesh(m, NavMeshConfig{radius});
      const std::vector<std::uint8_t> open = erodeWalkable(m, radius);
      std::vector<int> owner(open.size(), -1);
      for (int p = 0; p < int(mesh.polygons().size()); ++p) {
        const NavPolygon& r = mesh.polygons()[std::size_t(p)];
        ASSERT_LT(r.x0, r.x1);  // a non-empty rectangle: convex
        ASSERT_LT(r.y0, r.y1);
        for (int y = r.y0; y < r.y1; ++y) {
          for (int x = r.x0; x < r.x1; ++x) {
            EXPECT_TRUE(open[std::size_t(m.index(x, y))]) << "seed " << seed << " r " << radius;
            EXPECT_EQ(owner[std::size_t(m.index(x, y))], -1) << "overlap at " << x << "," << y;
            owner[std::size_t(m.index(x, y))] = p;
            EXPECT_EQ(mesh.polygonAt(x, y), p);
          }
        }
      }
      for (std::size_t i = 0; i < open.size(); ++i)
        EXPECT_EQ(open[i] != 0, owner[i] >= 0) << "seed " << seed << " cell " << i;
      // Each portal lies on both polygons' boundaries, and each polygon lists it.
      for (int e = 0; e < int(mesh.portals().size()); ++e) {
        const NavPortal& pt = mesh.portals()[std::size_t(e)];
        const NavPolygon& a = mesh.polygons()[std::size_t(pt.low)];
        const NavPolygon& b = mesh.polygons()[std::size_t(pt.high)];
        if (pt.x0 == pt.x1) {
          EXPECT_EQ(a.x1, pt.x0);
          EXPECT_EQ(b.x0, pt.x0);
          EXPECT_EQ(pt.y0, std::max(a.y0, b.y0));
          EXPECT_EQ(pt.y1, std::min(a.y1, b.y1));
        } else {
          EXPECT_EQ(a.y1, pt.y0);
          EXPECT_EQ(b.y0, pt.y0);
          EXPECT_EQ(pt.x0, std::max(a.x0, b.x0));
          EXPECT_EQ(pt.x1, std::min(a.x1, b.x1));
        }
        EXPECT_TRUE(pt.x0 < pt.x1 || pt.y0 < pt.y1);
        for (std::int32_t side : {pt.low, pt.high})
          EXPECT_NE(std::find(mesh.portalsBegin(side), mesh.portalsEnd(side), e),
                    mesh.portalsEnd(side));
      }
    }
  }
}

TEST(NavMeshTest, ErosionKeepsTheRadiusFromEveryWallAndTheEdge) {
  GridMap m = test::randomMap(24, 20, 0.1, 5);
  for (double radius : {0.0, 0.5, 1.0, 1.2, 2.5}) {
    const std::vector<std::uint8_t> open = erodeWalkable(m, radius);
    for (int y = 0; y < m.height(); ++y) {
      for (int x = 0; x < m.width(); ++x) {
        // Brute force: the gap from this cell's square to every blocked square, off-map
        // cells included.
        double gap = 1e9;
        for (int by = -1; by <= m.height(); ++by)
          for (int bx = -1; bx <= m.width(); ++bx)
            if (!m.passable(bx, by))
              gap = std::min(gap, std::hypot(std::max(0, std::abs(bx - x) - 1),
                                             std::max(0, std::abs(by - y) - 1)));
        const bool keep = m.passable(x, y) && gap >= radius;
        EXPECT_EQ(open[std::size_t(m.index(x, y))] != 0, keep)
            << "cell " << x << "," << y << " radius " << radius;
      }
    }
  }
}

TEST(NavMeshTest, SegmentsCrossInteriorsAndTouchEdgesAndCorners) {
  // Along the edge y = 5 between cells (20, 4) and (20, 5): crosses neither, touches both.
  const Vec2 a{20, 5}, b{21, 5};
  EXPECT_FALSE(segmentCrossesCell(a, b, Cell{20, 4}));
  EXPECT_FALSE(segmentCrossesCell(a, b, Cell{20, 5}));
  EXPECT_TRUE(segmentMeetsCell(a, b, Cell{20, 4}, CellContact::Closed));
  EXPECT_TRUE(segmentMeetsCell(a, b, Cell{20, 5}, CellContact::Closed));
  // Through the corner (1, 1) diagonally: crosses (0, 0) and (1, 1), only touches (1, 0).
  const Vec2 c{0.5, 0.5}, d{1.5, 1.5};
  EXPECT_TRUE(segmentCrossesCell(c, d, Cell{0, 0}));
  EXPECT_TRUE(segmentCrossesCell(c, d, Cell{1, 1}));
  EXPECT_FALSE(segmentCrossesCell(c, d, Cell{1, 0}));
  EXPECT_TRUE(segmentMeetsCell(c, d, Cell{1, 0}, CellContact::Closed));
  int touched = 0;
  forEachCellMet(c, d, CellContact::Closed, [&](Cell) { ++touched; });
  EXPECT_EQ(touched, 4);
  int crossed = 0;
  forEachCellCrossed(Vec2{0.5, 0.5}, Vec2{7.5, 2.5}, [&](Cell) { ++crossed; });
  EXPECT_EQ(crossed, 10);  // 7 column and 2 row changes after the first, no lattice point
}

TEST(NavMeshTest, FunnelTurnsAtTheInnerCornerOnly) {
  // An L: along y = 0.5 to the east, then up through a portal at x in [4, 5], y = 1.
  const std::vector<FunnelPortal> portals{{Vec2{4, 1}, Vec2{5, 1}}};
  // Travelling +y through a horizontal portal, left is the smaller x.
  std::vector<Vec2> path = pullString(Vec2{0.5, 0.5}, portals, Vec2{4.5, 5.5});
  ASSERT_EQ(path.size(), 3u);
  EXPECT_EQ(path[1], (Vec2{4, 1}));
  // A straight view through the portal keeps two points.
  path = pullString(Vec2{4.5, 0.5}, portals, Vec2{4.5, 5.5});
  EXPECT_EQ(path.size(), 2u);
}

TEST(NavMeshTest, PathsOnRandomMapsStayOnTheMeshAndNearTheGridOptimum) {
  int found = 0, none = 0, shorter = 0, longer = 0;
  double worst = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    GridMap m = test::randomMap(48, 40, 0.05 + 0.01 * double(seed % 30), seed);
    NavMesh mesh(m, NavMeshConfig{});
    NavMeshSearch search(mesh);
    const std::vector<std::uint8_t> open = erodeWalkable(m, 0);
    NavPath path;
    Pcg32 rng(seed, 3);
    for (int q = 0; q < 25; ++q) {
      const Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
      const double optimum = test::referenceDistance(m, s, g);
      const bool ok = search.findPath(s, g, path);
      ASSERT_EQ(ok, optimum >= 0) << "seed " << seed << " query " << q;
      if (!ok) {
        EXPECT_TRUE(path.points.empty());
        ++none;
        continue;
      }
      ++found;
      EXPECT_EQ(crossingsOff(open, m.width(), m.height(), path), 0) << "seed " << seed;
      EXPECT_EQ(path.points.front(), (Vec2{s.x + 0.5, s.y + 0.5}));
      EXPECT_EQ(path.points.back(), (Vec2{g.x + 0.5, g.y + 0.5}));
      EXPECT_GE(path.length, std::hypot(g.x - s.x, g.y - s.y) - 1e-9);
      if (optimum > 0) worst = std::max(worst, path.length / optimum);
      if (path.length < optimum - 1e-9) ++shorter;
      if (path.length > optimum + 1e-9) ++longer;
    }
  }
  EXPECT_GT(found, 700);
  EXPECT_GT(none, 5);
  EXPECT_GT(shorter, found / 2);  // any-angle segments beat 45-degree steps
  // The corridor the portal search picks is not always the best one: on these small, dense
  // maps 2 paths of 971 end longer than the grid optimum, the worst by 18% (a short path
  // round the wrong side of an obstacle).
  EXPECT_LT(longer, found / 100);
  EXPECT_LE(worst, 1.2) << "worst navmesh length over the 8-connected optimum";
}

TEST(NavMeshTest, PathsWithARadiusNeverEnterTheErodedBorder) {
  int found = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    GridMap m = test::randomMap(60, 50, 0.03, seed);
    for (double radius : {0.4, 1.0}) {
      NavMesh mesh(m, NavMeshConfig{radius});
      NavMeshSearch search(mesh);
      const std::vector<std::uint8_t> open = erodeWalkable(m, radius);
      NavPath path;
      Pcg32 rng(seed, 9);
      for (int q = 0; q < 20; ++q) {
        const Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
        if (!open[std::size_t(m.index(s.x, s.y))] || !open[std::size_t(m.index(g.x, g.y))])
          continue;
        if (!search.findPath(s, g, path)) continue;
        ++found;
        EXPECT_EQ(crossingsOff(open, m.width(), m.height(), path), 0) << "seed " << seed;
      }
    }
  }
  EXPECT_GT(found, 300);
}

TEST(NavMeshTest, MovingAiPathsNeverCrossABlockedCell) {
  // Radius 0: the mesh covers every passable cell, as the grid optimum assumes.
  for (const char* map : {"random512-10-0.map", "8room_000.map", "maze512-1-0.map"}) {
    GridMap m = loadMovingAiMap(test::movingAiPath(map));
    auto problems = loadScenario(test::movingAiPath(std::string(map) + ".scen"));
    NavMesh mesh(m, NavMeshConfig{});
    NavMeshSearch search(mesh);
    const std::vector<std::uint8_t> open = erodeWalkable(m, 0);
    NavPath path;
    int checked = 0, shorter = 0;
    double worst = 0;
    for (std::size_t i = 0; i < problems.size(); i += 11, ++checked) {
      const auto& p = problems[i];
      ASSERT_TRUE(search.findPath(p.start, p.goal, path)) << map << " line " << p.line;
      EXPECT_EQ(crossingsOff(open, m.width(), m.height(), path), 0) << map << " line " << p.line;
      EXPECT_GE(path.length, std::hypot(p.goal.x - p.start.x, p.goal.y - p.start.y) - 1e-9);
      if (p.optimal > 0) worst = std::max(worst, path.length / p.optimal);
      if (path.length < p.optimal - p.optimal_step) ++shorter;
    }
    EXPECT_GT(checked, 150) << map;
    EXPECT_GT(shorter, checked / 2) << map;
    EXPECT_LE(worst, 1.0 + 1e-6) << map << ": worst length over the listed optimum";
  }
}

TEST(NavMeshTest, StaticBoxesCloseTheCellsTheyOverlap) {
  GridMap m(20, 10);
  closeBoxes(m, {NavBox{4.5, 2.0, 6.0, 3.5}, NavBox{10, 0, 10, 9}});  // the second has no area
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 20; ++x)
      EXPECT_EQ(m.passable(x, y), !(x >= 4 && x <= 5 && y >= 2 && y <= 3)) << x << "," << y;
  // A wall of boxes with a gap: the path goes through the gap and crosses no box cell.
  GridMap open(20, 10);
  NavMesh mesh(open, {NavBox{9, 0, 11, 7}}, NavMeshConfig{});
  NavMeshSearch search(mesh);
  NavPath path;
  ASSERT_TRUE(search.findPath(Cell{2, 2}, Cell{17, 2}, path));
  GridMap closed = open;
  closeBoxes(closed, {NavBox{9, 0, 11, 7}});
  EXPECT_EQ(crossingsOff(erodeWalkable(closed, 0), 20, 10, path), 0);
  EXPECT_GT(path.length, 15.0);
  EXPECT_EQ(mesh.polygonAt(9, 3), -1);
}

TEST(NavMeshTest, UnreachableGoalsHaveNoPath) {
  GridMap m(30, 20);
  for (int y = 0; y < 20; ++y) m.setPassable(15, y, false);
  NavMesh mesh(m, NavMeshConfig{});
  NavMeshSearch search(mesh);
  NavPath path;
  EXPECT_FALSE(search.findPath(Cell{2, 10}, Cell{27, 10}, path));
  EXPECT_TRUE(path.points.empty());
  m.setPassable(15, 3, true);
  NavMesh door(m, NavMeshConfig{});
  NavMeshSearch through(door);
  ASSERT_TRUE(through.findPath(Cell{2, 10}, Cell{27, 10}, path));
  EXPECT_GT(path.points.size(), 2u);
}

TEST(NavMeshTest, BadInputIsRefusedWithAClearError) {
  GridMap m(10, 10);
  m.setPassable(3, 3, false);
  EXPECT_NE(message([&] { NavMesh(m, NavMeshConfig{-1.0}); }).find("agent_radius -1"),
            std::string::npos);
  EXPECT_NE(message([&] { NavMesh(m, NavMeshConfig{std::nan("")}); }).find("agent_radius"),
            std::string::npos);
  NavMesh mesh(m, NavMeshConfig{});
  NavMeshSearch search(mesh);
  NavPath path;
  EXPECT_EQ(message([&] {
              search.findPath(Cell{3, 3}, Cell{8, 8}, path);
            }),
            "navmesh: start (3.5, 3.5) is off the mesh: cell (3, 3) is blocked or within the "
            "agent radius (0) of a wall");
  EXPECT_EQ(message([&] {
              search.findPath(Vec2{1, 1}, Vec2{12, 1}, path);
            }),
            "navmesh: goal (12, 1) is off the mesh: outside the 10 x 10 map");
  NavMesh eroded(m, NavMeshConfig{1.0});
  NavMeshSearch near_wall(eroded);
  EXPECT_NE(message([&] {
              near_wall.findPath(Cell{0, 5}, Cell{5, 5}, path);
            }).find("within the agent radius (1) of a wall"),
            std::string::npos);
}

TEST(NavMeshTest, TheSameQueryGivesTheSamePath) {
  GridMap m = loadMovingAiMap(test::movingAiPath("8room_000.map"));
  NavMesh a(m, NavMeshConfig{}), b(m, NavMeshConfig{});
  NavMeshSearch sa(a), sb(b);
  NavPath pa, pb;
  auto problems = loadScenario(test::movingAiPath("8room_000.map.scen"));
  for (std::size_t i = 0; i < problems.size(); i += 97) {
    ASSERT_TRUE(sa.findPath(problems[i].start, problems[i].goal, pa));
    ASSERT_TRUE(sb.findPath(problems[i].start, problems[i].goal, pb));
    EXPECT_EQ(pa.points, pb.points);
    ASSERT_TRUE(sa.findPath(problems[i].start, problems[i].goal, pb));  // a reused searcher
    EXPECT_EQ(pa.points.size(), pb.points.size());
    for (std::size_t k = 0; k < pa.points.size() && k < pb.points.size(); ++k)
      EXPECT_EQ(pa.points[k], pb.points[k]);
  }
}

}  // namespace
}  // namespace zonesim::ai
