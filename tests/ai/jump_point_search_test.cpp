// Jump point search (scanned and JPS+): the same optimal lengths as an independent Dijkstra on
// random maps of every density, every cell of the path a legal move, no corner cutting, doors
// that open and close between searches, and the Moving AI optima on a subset of each file (the
// whole files run through scen_check --planner jps / jps+, see CMakeLists.txt).

#include "ai/jump_point_search.h"

#include <gtest/gtest.h>

#include "ai/scenario.h"
#include "tests/ai/reference_dijkstra.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

using Jumps = JumpPointSearch::Jumps;

class JumpPointSearchTest : public ::testing::TestWithParam<Jumps> {};

TEST_P(JumpPointSearchTest, EqualsDijkstraOnRandomMaps) {
  int found_paths = 0, no_paths = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const double density = 0.05 + 0.01 * double(seed % 40);
    GridMap m = test::randomMap(48, 40, density, seed);
    JumpPointSearch search(m, GetParam());
    GridPath path;
    Pcg32 rng(seed, 11);
    for (int q = 0; q < 25; ++q) {
      const Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
      const double expected = test::referenceDistance(m, s, g);
      const bool found = search.findPath(s, g, path);
      ASSERT_EQ(found, expected >= 0) << "seed " << seed << " query " << q;
      if (!found) {
        EXPECT_TRUE(path.cells.empty());
        ++no_paths;
        continue;
      }
      ++found_paths;
      EXPECT_NEAR(path.length, expected, 1e-9) << "seed " << seed << " query " << q;
      EXPECT_TRUE(isValidPath(m, path.cells)) << "seed " << seed << " query " << q;
      EXPECT_EQ(path.cells.front(), s);
      EXPECT_EQ(path.cells.back(), g);
    }
  }
  EXPECT_GT(found_paths, 1000);
  EXPECT_GT(no_paths, 10);  // the dense maps cut some cells off
}

TEST_P(JumpPointSearchTest, GoesAroundACornerInsteadOfCuttingIt) {
  // # .      (0, 0) is blocked: the diagonal from (0, 1) to (1, 0) would cut its corner, so the
  // . .      path takes the two cardinal steps round (1, 1): length 2, not sqrt 2.
  GridMap m(2, 2);
  m.setPassable(1, 0, true);
  m.setPassable(0, 0, false);
  JumpPointSearch search(m, GetParam());
  GridPath path;
  ASSERT_TRUE(search.findPath(Cell{0, 1}, Cell{1, 0}, path));
  EXPECT_DOUBLE_EQ(path.length, 2.0);
  EXPECT_TRUE(isValidPath(m, path.cells));
}

TEST_P(JumpPointSearchTest, FollowsADoorThatOpensAndCloses) {
  // A wall across the map with one door: closed, the goal is cut off; open, the path goes
  // through it; the searcher notices each change (its copy and tables follow the map).
  GridMap m(30, 20);
  for (int y = 0; y < 20; ++y) m.setPassable(15, y, false);
  JumpPointSearch search(m, GetParam());
  GridPath path;
  EXPECT_FALSE(search.findPath(Cell{2, 10}, Cell{27, 10}, path));
  m.setPassable(15, 3, true);
  ASSERT_TRUE(search.findPath(Cell{2, 10}, Cell{27, 10}, path));
  EXPECT_NEAR(path.length, test::referenceDistance(m, Cell{2, 10}, Cell{27, 10}), 1e-9);
  EXPECT_TRUE(isValidPath(m, path.cells));
  m.setPassable(15, 3, false);
  EXPECT_FALSE(search.findPath(Cell{2, 10}, Cell{27, 10}, path));
  EXPECT_FALSE(search.findPath(Cell{15, 3}, Cell{27, 10}, path));  // a blocked start
}

TEST_P(JumpPointSearchTest, MatchesTheMovingAiOptimaOnASubsetOfEachFile) {
  for (const char* map : {"random512-10-0.map", "8room_000.map", "maze512-1-0.map"}) {
    GridMap m = loadMovingAiMap(test::movingAiPath(map));
    auto problems = loadScenario(test::movingAiPath(std::string(map) + ".scen"));
    JumpPointSearch search(m, GetParam());
    GridPath path;
    int checked = 0;
    for (std::size_t i = 0; i < problems.size(); i += 37, ++checked) {
      const auto& p = problems[i];
      ASSERT_TRUE(search.findPath(p.start, p.goal, path)) << map << " line " << p.line;
      EXPECT_TRUE(agreesWithListed(path.length, p)) << map << " line " << p.line;
      EXPECT_TRUE(isValidPath(m, path.cells)) << map << " line " << p.line;
    }
    EXPECT_GT(checked, 40);
  }
}

INSTANTIATE_TEST_SUITE_P(Jumps, JumpPointSearchTest,
                         ::testing::Values(Jumps::Scanned, Jumps::Precomputed),
                         [](const auto& info) {
                           return info.param == Jumps::Scanned ? "Scanned" : "Precomputed";
                         });

}  // namespace
}  // namespace zonesim::ai
