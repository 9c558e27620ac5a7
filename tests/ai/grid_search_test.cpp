// A*: the listed optimal lengths of the Moving AI scenarios, equality with Dijkstra on random
// maps, corner cutting, bounds, and reuse of one searcher across queries.

#include "ai/grid_search.h"

#include <gtest/gtest.h>

#include "ai/scenario.h"
#include "tests/ai/reference_dijkstra.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

// Every `stride`-th problem plus the last (longest) ones: the whole files run through
// scen_check (see CMakeLists.txt); this keeps the unit test to seconds on two cores.
void checkScenario(const std::string& map, int stride) {
  GridMap m = loadMovingAiMap(test::movingAiPath(map));
  auto problems = loadScenario(test::movingAiPath(map + ".scen"));
  GridSearch search(m);
  GridPath path;
  int checked = 0;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    if (i % std::size_t(stride) != 0 && i + 3 < problems.size()) continue;
    const auto& p = problems[i];
    ASSERT_TRUE(search.findPath(p.start, p.goal, path)) << map << " line " << p.line;
    EXPECT_TRUE(lengthsAgree(path.length, p.optimal))
        << map << " line " << p.line << ": " << path.length << " vs " << p.optimal;
    EXPECT_NEAR(pathLength(path.cells), path.length, 1e-9);
    EXPECT_TRUE(isValidPath(m, path.cells)) << map << " line " << p.line;
    EXPECT_EQ(path.cells.front(), p.start);
    EXPECT_EQ(path.cells.back(), p.goal);
    ++checked;
  }
  EXPECT_GT(checked, 40);
}

TEST(GridSearchScenario, Random512) {
  checkScenario("random512-10-0.map", 5);
}
TEST(GridSearchScenario, Rooms) {
  checkScenario("8room_000.map", 15);
}
TEST(GridSearchScenario, Maze) {
  checkScenario("maze512-1-0.map", 80);
}

TEST(GridSearch, EqualsDijkstraOnRandomMaps) {
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    double density = 0.05 + 0.01 * double(seed % 30);
    GridMap m = test::randomMap(48, 40, density, seed);
    GridSearch search(m);
    GridPath path;
    Pcg32 rng(seed, 11);
    for (int q = 0; q < 25; ++q) {
      Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
      double expected = test::referenceDistance(m, s, g);
      bool found = search.findPath(s, g, path);
      ASSERT_EQ(found, expected >= 0) << "seed " << seed;
      if (!found) {
        EXPECT_TRUE(path.cells.empty());
        continue;
      }
      EXPECT_NEAR(path.length, expected, 1e-9) << "seed " << seed;
      EXPECT_TRUE(isValidPath(m, path.cells));
    }
  }
}

TEST(GridSearch, DoesNotCutCorners) {
  // . @
  // . .   a diagonal from (0,0) to (1,1) would clip the blocked corner.
  GridMap m(2, 2);
  m.setPassable(1, 0, false);
  GridSearch search(m);
  GridPath path;
  ASSERT_TRUE(search.findPath({0, 0}, {1, 1}, path));
  EXPECT_DOUBLE_EQ(path.length, 2.0);
  EXPECT_EQ(path.cells.size(), 3u);
  // Two blocked corners: the diagonal squeeze between them is not a path.
  m.setPassable(0, 1, false);
  EXPECT_FALSE(search.findPath({0, 0}, {1, 1}, path));
  EXPECT_TRUE(path.cells.empty());
}

TEST(GridSearch, OpenGridCostsOctile) {
  GridMap m(20, 20);
  GridSearch search(m);
  GridPath path;
  ASSERT_TRUE(search.findPath({1, 2}, {15, 7}, path));
  EXPECT_NEAR(path.length, 9.0 + 5.0 * std::sqrt(2.0), 1e-12);
  ASSERT_TRUE(search.findPath({3, 3}, {3, 3}, path));
  EXPECT_EQ(path.cells.size(), 1u);
  EXPECT_EQ(path.length, 0.0);
}

TEST(GridSearch, BlockedEndsHaveNoPath) {
  GridMap m(5, 5);
  m.setPassable(4, 4, false);
  GridSearch search(m);
  GridPath path;
  EXPECT_FALSE(search.findPath({0, 0}, {4, 4}, path));
  EXPECT_FALSE(search.findPath({4, 4}, {0, 0}, path));
  EXPECT_FALSE(search.findPath({0, 0}, {9, 9}, path));
}

TEST(GridSearch, BoundsConfineTheSearch) {
  // A wall with a gap outside the bounds: inside the bounds the goal is unreachable.
  GridMap m(10, 10);
  for (int y = 0; y < 9; ++y) m.setPassable(5, y, false);
  GridSearch search(m);
  GridPath path;
  ASSERT_TRUE(search.findPath({0, 0}, {9, 0}, path));
  EXPECT_FALSE(search.findPath({0, 0}, {9, 0}, CellRect{0, 0, 10, 8}, path));
  search.explore({0, 0}, CellRect{0, 0, 5, 5});
  EXPECT_DOUBLE_EQ(search.distanceTo({4, 0}), 4.0);
  EXPECT_LT(search.distanceTo({9, 0}), 0.0);
  search.pathTo({4, 4}, path);
  EXPECT_NEAR(path.length, 4.0 * std::sqrt(2.0), 1e-12);
}

TEST(GridSearch, ReuseGivesTheSamePathAndStopsAllocating) {
  GridMap m = test::randomMap(128, 128, 0.2, 99);
  GridSearch search(m);
  Pcg32 rng(5, 5);
  std::vector<std::pair<Cell, Cell>> queries;
  for (int i = 0; i < 30; ++i) {
    queries.push_back({test::randomFreeCell(m, rng), test::randomFreeCell(m, rng)});
  }
  std::vector<GridPath> first(queries.size());
  for (std::size_t i = 0; i < queries.size(); ++i) {
    search.findPath(queries[i].first, queries[i].second, first[i]);
  }
  // The first pass took the open list to its peak; the same queries cannot grow it again.
  const auto warm = search.storageCapacity();
  EXPECT_GT(warm.second, 0u);
  // Same queries again, in reverse order, through one output path whose storage is reused.
  GridPath path;
  path.cells.reserve(128 * 128);
  const Cell* storage = path.cells.data();
  for (std::size_t k = queries.size(); k-- > 0;) {
    search.findPath(queries[k].first, queries[k].second, path);
    EXPECT_EQ(path.cells, first[k].cells) << "query " << k;
    EXPECT_EQ(path.length, first[k].length);
    EXPECT_EQ(search.storageCapacity(), warm) << "query " << k;
  }
  EXPECT_EQ(path.cells.data(), storage);
}

}  // namespace
}  // namespace zonesim::ai
