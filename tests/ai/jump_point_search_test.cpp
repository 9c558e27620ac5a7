// Jump point search (scanned and JPS+, each with and without landmarks): the same optimal lengths
// as an independent Dijkstra on random maps of every density, every cell of the path a legal move,
// no corner cutting, doors that open and close between searches, and the Moving AI optima on a
// subset of each file (the whole files run through scen_check --planner jps / jps+, see
// CMakeLists.txt).

#include "ai/jump_point_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "ai/scenario.h"
#include "tests/ai/reference_dijkstra.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

using Jumps = JumpPointSearch::Jumps;

/// Scanned or precomputed jumps, with the octile estimate alone or with landmarks.
struct Variant {
  Jumps jumps;
  int landmarks;  // 0: none
};

void PrintTo(const Variant& v, std::ostream* os) {
  *os << (v.jumps == Jumps::Scanned ? "scanned" : "precomputed") << " jumps, " << v.landmarks
      << " landmarks";
}

class JumpPointSearchTest : public ::testing::TestWithParam<Variant> {
 protected:
  /// A searcher of this variant for `m`, its landmarks built for the map as it is now.
  JumpPointSearch searcher(const GridMap& m) {
    landmarks_.reset();
    if (GetParam().landmarks > 0)
      landmarks_ = std::make_unique<LandmarkHeuristic>(m, GetParam().landmarks);
    return JumpPointSearch(m, GetParam().jumps, landmarks_.get());
  }

 private:
  std::unique_ptr<LandmarkHeuristic> landmarks_;
};

TEST_P(JumpPointSearchTest, EqualsDijkstraOnRandomMaps) {
  int found_paths = 0, no_paths = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const double density = 0.05 + 0.01 * double(seed % 40);
    GridMap m = test::randomMap(48, 40, density, seed);
    JumpPointSearch search = searcher(m);
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

/// A 1-wide maze of (2 * n + 1)^2 cells carved by a depth-first walk, then `loops` walls
/// knocked out between corridors so that some bends lie on rings.
GridMap corridorMaze(int n, int loops, std::uint64_t seed) {
  const int size = 2 * n + 1;
  GridMap m(size, size);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) m.setPassable(x, y, x % 2 == 1 && y % 2 == 1);
  Pcg32 rng(seed, 5);
  std::vector<char> seen(std::size_t(n * n), 0);
  std::vector<std::pair<int, int>> stack{{0, 0}};
  seen[0] = 1;
  while (!stack.empty()) {
    const auto [cx, cy] = stack.back();
    std::pair<int, int> next[4];
    int count = 0;
    for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int nx = cx + dx, ny = cy + dy;
      if (nx >= 0 && ny >= 0 && nx < n && ny < n && !seen[std::size_t(ny * n + nx)])
        next[count++] = {nx, ny};
    }
    if (count == 0) {
      stack.pop_back();
      continue;
    }
    const auto [nx, ny] = next[rng.next() % std::uint32_t(count)];
    seen[std::size_t(ny * n + nx)] = 1;
    m.setPassable(cx + nx + 1, cy + ny + 1, true);  // the wall between the two rooms
    stack.push_back({nx, ny});
  }
  for (int k = 0; k < loops; ++k) {
    // A wall cell between two corridor cells, in a row or in a column.
    const int a = 1 + 2 * int(rng.next() % std::uint32_t(n)),
              b = 2 + 2 * int(rng.next() % std::uint32_t(n - 1));
    if (rng.next() % 2 == 0) {
      m.setPassable(b, a, true);
    } else {
      m.setPassable(a, b, true);
    }
  }
  return m;
}

TEST_P(JumpPointSearchTest, EqualsDijkstraInCorridorMazes) {
  // Every corridor bend is turned within a jump (never an open-list node): paths round them,
  // along rings (the loops) and into dead ends must stay optimal and legal.
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    GridMap m = corridorMaze(14, int(seed % 4) * 20, seed);
    JumpPointSearch search = searcher(m);
    GridPath path;
    Pcg32 rng(seed, 13);
    for (int q = 0; q < 30; ++q, ++checked) {
      const Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
      ASSERT_TRUE(search.findPath(s, g, path)) << "seed " << seed << " query " << q;
      EXPECT_NEAR(path.length, test::referenceDistance(m, s, g), 1e-9)
          << "seed " << seed << " query " << q;
      EXPECT_TRUE(isValidPath(m, path.cells)) << "seed " << seed << " query " << q;
      EXPECT_EQ(path.cells.front(), s);
      EXPECT_EQ(path.cells.back(), g);
    }
  }
  EXPECT_EQ(checked, 900);
}

TEST_P(JumpPointSearchTest, StaysOptimalWhenItsStampsWrapAround) {
  // Node states are 16-bit generation stamps, reset when they wrap (every 21,845 searches):
  // searches on either side of the wrap must not see each other's records.
  GridMap m = test::randomMap(12, 10, 0.2, 3);
  JumpPointSearch search = searcher(m);
  GridPath path;
  Pcg32 rng(3, 17);
  int wrong = 0;
  for (int q = 0; q < 23000; ++q) {
    const Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
    const double expected = test::referenceDistance(m, s, g);
    const bool found = search.findPath(s, g, path);
    if (found != (expected >= 0) || (found && std::abs(path.length - expected) > 1e-9)) ++wrong;
  }
  EXPECT_EQ(wrong, 0);
}

TEST_P(JumpPointSearchTest, GoesAroundACornerInsteadOfCuttingIt) {
  // # .      (0, 0) is blocked: the diagonal from (0, 1) to (1, 0) would cut its corner, so the
  // . .      path takes the two cardinal steps round (1, 1): length 2, not sqrt 2.
  GridMap m(2, 2);
  m.setPassable(1, 0, true);
  m.setPassable(0, 0, false);
  JumpPointSearch search = searcher(m);
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
  JumpPointSearch search = searcher(m);
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
    JumpPointSearch search = searcher(m);
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

INSTANTIATE_TEST_SUITE_P(
    Jumps, JumpPointSearchTest,
    ::testing::Values(Variant{Jumps::Scanned, 0}, Variant{Jumps::Precomputed, 0},
                      Variant{Jumps::Scanned, 6}, Variant{Jumps::Precomputed, 6}),
    [](const auto& info) {
      return std::string(info.param.jumps == Jumps::Scanned ? "Scanned" : "Precomputed") +
             (info.param.landmarks > 0 ? "Landmarks" : "");
    });

}  // namespace
}  // namespace zonesim::ai
