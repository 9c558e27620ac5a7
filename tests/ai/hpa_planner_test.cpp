// HPA*: complete and never shorter than optimal, overhead bounded on the shipped maps, and a
// local repair after a door closes gives the same answers as rebuilding from scratch.

#include "ai/hpa_planner.h"

#include <gtest/gtest.h>

#include "ai/grid_search.h"
#include "ai/scenario.h"
#include "tests/ai/reference_dijkstra.h"
#include "tests/ai/test_data.h"

namespace zonesim::ai {
namespace {

/// The abstraction alone: no query is handed to the direct search, however short.
HpaConfig abstractOnly(int cluster_size = 16, int wide_entrance = 6, int smooth_span = 0) {
  HpaConfig c{cluster_size, wide_entrance, smooth_span};
  c.direct_distance = -1.0;
  return c;
}

TEST(HpaPlanner, ScenariosAreCompleteWithBoundedOverhead) {
  for (const char* name : {"random512-10-0.map", "8room_000.map", "maze512-1-0.map"}) {
    GridMap m = loadMovingAiMap(test::movingAiPath(name));
    auto problems = loadScenario(test::movingAiPath(std::string(name) + ".scen"));
    HpaPlanner hpa(m, abstractOnly());
    GridPath path;
    double worst = 0.0;
    for (std::size_t i = 0; i < problems.size(); i += 7) {
      const auto& p = problems[i];
      ASSERT_TRUE(hpa.findPath(p.start, p.goal, path)) << name << " line " << p.line;
      ASSERT_TRUE(isValidPath(m, path.cells)) << name << " line " << p.line;
      EXPECT_EQ(path.cells.front(), p.start);
      EXPECT_EQ(path.cells.back(), p.goal);
      EXPECT_GE(path.length, p.optimal * (1 - 1e-3) - 1e-3) << name << " line " << p.line;
      if (p.optimal > 0) worst = std::max(worst, path.length / p.optimal - 1.0);
    }
    // HPA* without smoothing: short paths near cluster borders detour the most.
    EXPECT_LT(worst, 1.0) << name;
  }
}

TEST(HpaPlanner, SmoothingNeverLengthensAndCutsTheOverhead) {
  GridMap m = loadMovingAiMap(test::movingAiPath("random512-10-0.map"));
  auto problems = loadScenario(test::movingAiPath("random512-10-0.map.scen"));
  HpaPlanner raw(m, abstractOnly(16, 6, 0));
  HpaPlanner smooth(m, abstractOnly(16, 6, 3));
  GridPath a, b;
  double rawTotal = 0, smoothTotal = 0;
  for (std::size_t i = 0; i < problems.size(); i += 9) {
    const auto& p = problems[i];
    ASSERT_TRUE(raw.findPath(p.start, p.goal, a));
    ASSERT_TRUE(smooth.findPath(p.start, p.goal, b));
    ASSERT_TRUE(isValidPath(m, b.cells)) << "line " << p.line;
    EXPECT_EQ(b.cells.front(), p.start);
    EXPECT_EQ(b.cells.back(), p.goal);
    EXPECT_LE(b.length, a.length + 1e-9) << "line " << p.line;
    EXPECT_GE(b.length, p.optimal * (1 - 1e-3) - 1e-3) << "line " << p.line;
    rawTotal += a.length / p.optimal - 1;
    smoothTotal += b.length / p.optimal - 1;
  }
  EXPECT_LT(smoothTotal, rawTotal);
}

TEST(HpaPlanner, FindsAPathExactlyWhenOneExists) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    GridMap m = test::randomMap(70, 53, 0.1 + 0.02 * double(seed), seed);
    HpaPlanner hpa(m, abstractOnly(8, 6));
    GridPath path;
    Pcg32 rng(seed, 3);
    for (int q = 0; q < 30; ++q) {
      Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
      double best = test::referenceDistance(m, s, g);
      ASSERT_EQ(hpa.findPath(s, g, path), best >= 0) << "seed " << seed << " q " << q;
      if (best < 0) continue;
      EXPECT_TRUE(isValidPath(m, path.cells));
      EXPECT_GE(path.length, best - 1e-9);
      EXPECT_NEAR(path.length, pathLength(path.cells), 1e-9);
    }
  }
}

TEST(HpaPlanner, OpenMapIsNearOptimal) {
  GridMap m(64, 64);
  HpaPlanner hpa(m, abstractOnly());
  GridPath path;
  ASSERT_TRUE(hpa.findPath({2, 3}, {60, 50}, path));
  EXPECT_LE(path.length, octileDistance(Cell{2, 3}, Cell{60, 50}) * 1.1);
  ASSERT_TRUE(hpa.findPath({5, 5}, {5, 5}, path));
  EXPECT_EQ(path.cells.size(), 1u);
  EXPECT_EQ(hpa.stats().clusters, 16);
  EXPECT_GT(hpa.stats().nodes, 0);
}

// A wall across the map with one door; closing it must cut the map in two, reopening it must
// restore the route, and the local repair must agree with a fresh abstraction.
TEST(HpaPlanner, DoorClosingIsRepairedLocally) {
  GridMap m(64, 40);
  for (int y = 0; y < 40; ++y) m.setPassable(31, y, false);
  const Cell door{31, 20};
  m.setPassable(door.x, door.y, true);
  HpaPlanner hpa(m, abstractOnly(16, 6));
  GridPath path;
  ASSERT_TRUE(hpa.findPath({2, 2}, {60, 35}, path));
  EXPECT_NE(std::find(path.cells.begin(), path.cells.end(), door), path.cells.end());

  m.setPassable(door.x, door.y, false);
  hpa.cellChanged(door);
  EXPECT_FALSE(hpa.findPath({2, 2}, {60, 35}, path));

  m.setPassable(door.x, door.y, true);
  hpa.cellChanged(door);
  ASSERT_TRUE(hpa.findPath({2, 2}, {60, 35}, path));
  double repaired = path.length;
  HpaPlanner fresh(m, abstractOnly(16, 6));
  GridPath freshPath;
  ASSERT_TRUE(fresh.findPath({2, 2}, {60, 35}, freshPath));
  EXPECT_EQ(path.cells, freshPath.cells);
  EXPECT_DOUBLE_EQ(repaired, freshPath.length);
  EXPECT_EQ(hpa.stats().nodes, fresh.stats().nodes);
  EXPECT_EQ(hpa.stats().edges, fresh.stats().edges);
}

TEST(HpaPlanner, RandomEditsRepairLikeARebuild) {
  GridMap m = test::randomMap(80, 64, 0.2, 77);
  HpaPlanner hpa(m, abstractOnly(8, 6));
  Pcg32 rng(77, 1);
  GridPath a, b;
  for (int edit = 0; edit < 40; ++edit) {
    Cell c{int(rng.next() % 80u), int(rng.next() % 64u)};
    m.setPassable(c.x, c.y, !m.passable(c.x, c.y));
    hpa.cellChanged(c);
    HpaPlanner fresh(m, abstractOnly(8, 6));
    EXPECT_EQ(hpa.stats().nodes, fresh.stats().nodes) << "edit " << edit;
    EXPECT_EQ(hpa.stats().edges, fresh.stats().edges) << "edit " << edit;
    Cell s = test::randomFreeCell(m, rng), g = test::randomFreeCell(m, rng);
    bool fa = hpa.findPath(s, g, a), fb = fresh.findPath(s, g, b);
    ASSERT_EQ(fa, fb) << "edit " << edit;
    EXPECT_EQ(a.cells, b.cells) << "edit " << edit;
  }
}

TEST(HpaPlanner, UnreportedChangesTriggerARebuild) {
  GridMap m(32, 32);
  for (int y = 0; y < 32; ++y) m.setPassable(16, y, false);
  m.setPassable(16, 5, true);
  HpaPlanner hpa(m, abstractOnly(8, 6));
  GridPath path;
  ASSERT_TRUE(hpa.findPath({1, 1}, {30, 30}, path));
  m.setPassable(16, 5, false);
  EXPECT_FALSE(hpa.findPath({1, 1}, {30, 30}, path));
}

}  // namespace
}  // namespace zonesim::ai

namespace zonesim::ai {
namespace {

// Short queries go to the optimal jump point search (HpaConfig::direct_distance), long ones
// through the abstraction: short paths come back optimal, and the choice is reported.
TEST(HpaPlannerDirect, ShortQueriesAreOptimalAndLongOnesUseTheAbstraction) {
  GridMap m = loadMovingAiMap(test::movingAiPath("random512-10-0.map"));
  auto problems = loadScenario(test::movingAiPath("random512-10-0.map.scen"));
  HpaPlanner hpa(m, HpaConfig{});
  GridPath path;
  int direct = 0, abstract = 0;
  for (std::size_t i = 0; i < problems.size(); i += 5) {
    const auto& p = problems[i];
    ASSERT_TRUE(hpa.findPath(p.start, p.goal, path)) << "line " << p.line;
    EXPECT_TRUE(isValidPath(m, path.cells)) << "line " << p.line;
    const bool short_query = octileDistance(p.start, p.goal) <= HpaConfig{}.direct_distance;
    EXPECT_EQ(hpa.stats().direct, short_query) << "line " << p.line;
    if (short_query) {
      ++direct;
      EXPECT_TRUE(agreesWithListed(path.length, p)) << "line " << p.line;
      EXPECT_EQ(hpa.stats().expanded, 0);  // no abstract node touched
    } else {
      ++abstract;
      EXPECT_GT(hpa.stats().expanded, 0);
    }
  }
  EXPECT_GT(direct, 20);
  EXPECT_GT(abstract, 100);
}

}  // namespace
}  // namespace zonesim::ai
