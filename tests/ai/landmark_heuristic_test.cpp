// The landmark (differential) heuristic: never above the true cost, consistent across every
// legal step (so jump point search and A* stay optimal with it), landmarks spread over the
// largest area, refused counts named, stale after a map change; and on the Moving AI maze it
// cuts the nodes jump point search expands; A* with them finds the optima (jump point search's
// optimality with landmarks is in jump_point_search_test.cpp).

#include "ai/landmark_heuristic.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "ai/fixed_cost.h"
#include "ai/grid_search.h"
#include "ai/jump_point_search.h"
#include "ai/scenario.h"
#include "tests/ai/reference_dijkstra.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

TEST(LandmarkHeuristic, NeverExceedsTheCostAndIsConsistentOverEveryStep) {
  int pairs = 0, steps = 0, exact = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    GridMap m = test::randomMap(40, 32, 0.05 + 0.03 * double(seed), seed);
    const LandmarkHeuristic h(m, 1 + int(seed % 6));
    LandmarkHeuristic::Goal goal;
    Pcg32 rng(seed, 3);
    for (int q = 0; q < 8; ++q) {
      const Cell g = test::randomFreeCell(m, rng);
      h.prepareGoal(g.x, g.y, goal);
      for (int y = 0; y < m.height(); ++y) {
        for (int x = 0; x < m.width(); ++x) {
          if (!m.passable(x, y)) continue;
          const std::int64_t here = h.bound(x, y, goal);
          // Consistent: no legal step lowers the bound by more than the step costs.
          for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
              if ((dx == 0 && dy == 0) || !m.passable(x + dx, y + dy)) continue;
              if (dx != 0 && dy != 0 && (!m.passable(x + dx, y) || !m.passable(x, y + dy)))
                continue;
              const std::int64_t step = dx != 0 && dy != 0 ? kDiagonal : kStraight;
              EXPECT_LE(here, step + h.bound(x + dx, y + dy, goal))
                  << "seed " << seed << " at (" << x << "," << y << ")";
              ++steps;
            }
          }
        }
      }
      // Admissible: never above the true cost of a reachable cell.
      for (int k = 0; k < 20; ++k, ++pairs) {
        const Cell s = test::randomFreeCell(m, rng);
        const double cost = test::referenceDistance(m, s, g);
        if (cost < 0) continue;
        const double bound = double(h.bound(s.x, s.y, goal)) / double(kStraight);
        EXPECT_LE(bound, cost + 1e-9) << "seed " << seed << " (" << s.x << "," << s.y << ")";
        exact += std::abs(bound - cost) < 1e-9;
      }
    }
  }
  EXPECT_GT(steps, 100000);
  EXPECT_EQ(pairs, 12 * 8 * 20);
  EXPECT_GT(exact, 20);  // and often exact: the start on a landmark's path to the goal
}

TEST(LandmarkHeuristic, SpreadsItsLandmarksOverTheLargestArea) {
  // A wall splits the map: 10 columns on the left, 29 on the right. Every landmark is on the
  // right, no two alike, and the first two are the area's far corners.
  GridMap m(40, 20);
  for (int y = 0; y < 20; ++y) m.setPassable(10, y, false);
  const LandmarkHeuristic h(m, 4);
  ASSERT_EQ(h.landmarks().size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_GT(h.landmarks()[i].x, 10);
    for (std::size_t j = 0; j < i; ++j) EXPECT_FALSE(h.landmarks()[i] == h.landmarks()[j]);
  }
  const Cell a = h.landmarks()[0], b = h.landmarks()[1];
  EXPECT_NEAR(octileDistance(a, b), octileDistance(Cell{11, 0}, Cell{39, 19}), 1e-9);
  EXPECT_EQ(h.bytes(), std::size_t(40 * 20 * 4) * sizeof(std::int64_t));
  // The left area is no landmark's: a goal there gets no bound but the octile one.
  LandmarkHeuristic::Goal goal;
  h.prepareGoal(3, 3, goal);
  EXPECT_TRUE(goal.landmark.empty());
  EXPECT_EQ(h.bound(5, 5, goal), 0);
}

TEST(LandmarkHeuristic, TakesNoMoreLandmarksThanTheAreaHasCells) {
  GridMap m(5, 1);
  m.setPassable(0, 0, false);
  m.setPassable(4, 0, false);
  const LandmarkHeuristic h(m, 8);
  EXPECT_EQ(h.landmarks().size(), 3u);
}

TEST(LandmarkHeuristic, RefusesACountOutOfRangeNamingIt) {
  GridMap m(8, 8);
  for (int count : {0, -2, LandmarkHeuristic::kMaxLandmarks + 1}) {
    try {
      LandmarkHeuristic h(m, count);
      ADD_FAILURE() << "count " << count << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("landmark count " + std::to_string(count)),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(LandmarkHeuristic, GoesStaleWhenTheMapChanges) {
  GridMap m(16, 16);
  const LandmarkHeuristic h(m, 2);
  EXPECT_TRUE(h.validFor(m));
  m.setPassable(4, 4, false);
  EXPECT_FALSE(h.validFor(m));
  EXPECT_FALSE(h.validFor(GridMap(16, 8)));
}

TEST(LandmarkHeuristic, AStarWithLandmarksStaysOptimalAndIgnoresThemOnceStale) {
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    GridMap m = test::randomMap(48, 40, 0.1 + 0.015 * double(seed), seed);
    const LandmarkHeuristic landmarks(m, 5);
    GridSearch search(m);
    search.useLandmarks(&landmarks);
    GridPath path;
    Pcg32 rng(seed, 21);
    for (int q = 0; q < 25; ++q) {
      if (q == 20) m.setPassable(int(rng.next() % 48u), int(rng.next() % 40u), true);  // stale
      const Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
      const double expected = test::referenceDistance(m, s, g);
      ASSERT_EQ(search.findPath(s, g, path), expected >= 0) << "seed " << seed << " q " << q;
      if (expected < 0) continue;
      EXPECT_NEAR(path.length, expected, 1e-9) << "seed " << seed << " q " << q;
      EXPECT_TRUE(isValidPath(m, path.cells));
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
}

TEST(LandmarkHeuristic, CutsTheNodesJumpPointSearchExpandsOnTheMaze) {
  // Counts, not times: every 37th problem of the Moving AI maze, with and without 8 landmarks,
  // the same optimal lengths.
  GridMap m = loadMovingAiMap(test::movingAiPath("maze512-1-0.map"));
  auto problems = loadScenario(test::movingAiPath("maze512-1-0.map.scen"));
  const LandmarkHeuristic landmarks(m, 8);
  JumpPointSearch plain(m), guided(m, JumpPointSearch::Jumps::Scanned, &landmarks);
  GridPath a, b;
  long plain_expanded = 0, guided_expanded = 0;
  for (std::size_t i = 0; i < problems.size(); i += 37) {
    const ScenarioProblem& p = problems[i];
    ASSERT_TRUE(plain.findPath(p.start, p.goal, a));
    ASSERT_TRUE(guided.findPath(p.start, p.goal, b));
    EXPECT_TRUE(agreesWithListed(b.length, p)) << "line " << p.line;
    EXPECT_NEAR(a.length, b.length, 1e-9) << "line " << p.line;
    plain_expanded += plain.lastStats().expanded;
    guided_expanded += guided.lastStats().expanded;
  }
  std::printf("maze, every 37th problem: %ld jump points expanded with 8 landmarks, %ld without\n",
              guided_expanded, plain_expanded);
  EXPECT_LT(guided_expanded * 3, plain_expanded)
      << "with landmarks " << guided_expanded << ", without " << plain_expanded;
}

}  // namespace
}  // namespace zonesim::ai
