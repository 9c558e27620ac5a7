// The path cache, the per-tick request budget, and re-planning when a door closes.

#include "ai/path_service.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "ai/segment_cells.h"
#include "tests/ai/reference_dijkstra.h"

namespace zonesim::ai {
namespace {

GridPath straight(Cell a, Cell b) {
  GridPath p;
  for (int x = a.x; x <= b.x; ++x) p.cells.push_back(Cell{x, a.y});
  p.length = pathLength(p.cells);
  return p;
}

TEST(PathCache, HitsEvictsLeastRecentlyUsedAndDropsPathsThroughAClosedCell) {
  PathCache cache(2);
  cache.insert({0, 0}, {3, 0}, straight({0, 0}, {3, 0}));
  cache.insert({0, 1}, {3, 1}, straight({0, 1}, {3, 1}));
  ASSERT_NE(cache.find({0, 0}, {3, 0}), nullptr);  // now the most recent
  cache.insert({0, 2}, {3, 2}, straight({0, 2}, {3, 2}));
  EXPECT_EQ(cache.find({0, 1}, {3, 1}), nullptr) << "least recently used is evicted";
  EXPECT_NE(cache.find({0, 2}, {3, 2}), nullptr);
  EXPECT_EQ(cache.hits(), 2u);
  EXPECT_EQ(cache.misses(), 1u);

  cache.cellClosed({2, 0});
  EXPECT_EQ(cache.find({0, 0}, {3, 0}), nullptr);
  EXPECT_NE(cache.find({0, 2}, {3, 2}), nullptr);
  cache.clear();
  EXPECT_EQ(cache.size(), 0u);
}

// Two rooms joined by two doors in a wall at x = 20: the near door at y = 5, the far at y = 35.
GridMap twoDoors() {
  GridMap m(40, 40);
  for (int y = 0; y < 40; ++y) m.setPassable(20, y, false);
  m.setPassable(20, 5, true);
  m.setPassable(20, 35, true);
  return m;
}

// A grid path of legal moves, or a navmesh path none of whose segments crosses a blocked cell
// and whose cells (those it touches) include its ends.
bool validPath(const GridMap& m, const GridPath& p) {
  if (p.points.empty()) return isValidPath(m, p.cells);
  for (std::size_t k = 1; k < p.points.size(); ++k) {
    bool blocked = false;
    forEachCellCrossed(p.points[k - 1], p.points[k],
                       [&](Cell c) { blocked = blocked || !m.passable(c.x, c.y); });
    if (blocked) return false;
  }
  return !p.cells.empty();
}

class PathServiceTest : public ::testing::TestWithParam<PlannerKind> {};

TEST_P(PathServiceTest, BudgetSpreadsRequestsOverTicks) {
  GridMap m = test::randomMap(64, 64, 0.15, 3);
  PathServiceConfig config;
  config.planner = GetParam();
  config.paths_per_tick = 4;
  PathService service(m, config);
  Pcg32 rng(3, 9);
  std::vector<PathRequestId> ids;
  for (int i = 0; i < 10; ++i) {
    ids.push_back(service.request(test::randomFreeCell(m, rng), test::randomFreeCell(m, rng)));
  }
  EXPECT_EQ(service.queued(), 10u);
  service.tick();
  EXPECT_EQ(service.stats().planned, 4u);
  EXPECT_EQ(service.queued(), 6u);
  service.tick();
  service.tick();
  EXPECT_EQ(service.stats().planned, 10u);
  EXPECT_EQ(service.queued(), 0u);
  for (PathRequestId id : ids) {
    EXPECT_NE(service.status(id), PathStatus::Queued);
    if (service.status(id) == PathStatus::Ready) {
      EXPECT_TRUE(validPath(m, service.path(id)));
    }
  }
}

TEST_P(PathServiceTest, ExpansionBudgetStopsATickButAlwaysPlansOne) {
  GridMap m = test::randomMap(96, 96, 0.15, 8);
  Pcg32 rng(8, 2);
  std::vector<std::pair<Cell, Cell>> queries;
  for (int i = 0; i < 12; ++i) {
    queries.push_back({test::randomFreeCell(m, rng), test::randomFreeCell(m, rng)});
  }
  std::uint64_t total = 0;
  auto ticksToServe = [&](int expansions_per_tick) {
    PathServiceConfig config;
    config.planner = GetParam();
    config.paths_per_tick = 100;
    config.expansions_per_tick = expansions_per_tick;
    config.cache_capacity = 0;
    PathService service(m, config);
    for (auto [s, g] : queries) service.request(s, g);
    int ticks = 0;
    std::uint64_t before = 0;
    while (service.queued() > 0) {
      service.tick();
      ++ticks;
      std::uint64_t planned = service.stats().planned - before;
      before = service.stats().planned;
      EXPECT_GE(planned, 1u) << "every tick makes progress";
    }
    EXPECT_EQ(service.stats().planned, queries.size());
    EXPECT_GT(service.stats().expanded, 0u);
    total = service.stats().expanded;
    return ticks;
  };
  EXPECT_EQ(ticksToServe(0), 1);
  EXPECT_EQ(ticksToServe(1), 12) << "a tiny budget still plans one request per tick";
  // A quarter of the whole work per tick: a few ticks, not one, not one per request.
  int middle = ticksToServe(int(total / 4));
  EXPECT_GT(middle, 1);
  EXPECT_LT(middle, 12);
}

TEST_P(PathServiceTest, RepeatedQueriesComeFromTheCacheAndCostNoBudget) {
  GridMap m = twoDoors();
  PathServiceConfig config;
  config.planner = GetParam();
  config.paths_per_tick = 1;
  PathService service(m, config);
  PathRequestId first = service.request({2, 2}, {38, 2});
  service.tick();
  ASSERT_EQ(service.status(first), PathStatus::Ready);
  std::vector<PathRequestId> again;
  for (int i = 0; i < 5; ++i) again.push_back(service.request({2, 2}, {38, 2}));
  service.tick();
  EXPECT_EQ(service.stats().planned, 1u);
  EXPECT_EQ(service.stats().cache_hits, 5u);
  for (PathRequestId id : again) EXPECT_EQ(service.path(id).cells, service.path(first).cells);
}

TEST_P(PathServiceTest, ClosingADoorReplansOnlyThePathsThroughIt) {
  GridMap m = twoDoors();
  PathServiceConfig config;
  config.planner = GetParam();
  PathService service(m, config);
  PathRequestId cross = service.request({2, 2}, {38, 2});
  PathRequestId local = service.request({2, 30}, {10, 38});
  service.tick();
  ASSERT_EQ(service.status(cross), PathStatus::Ready);
  const auto& before = service.path(cross).cells;
  ASSERT_NE(std::find(before.begin(), before.end(), Cell{20, 5}), before.end());
  GridPath localBefore = service.path(local);

  service.setCell({20, 5}, false);
  EXPECT_EQ(service.status(cross), PathStatus::Queued);
  EXPECT_EQ(service.status(local), PathStatus::Ready);
  EXPECT_EQ(service.stats().replans, 1u);
  service.tick();
  ASSERT_EQ(service.status(cross), PathStatus::Ready);
  const auto& after = service.path(cross).cells;
  EXPECT_TRUE(validPath(m, service.path(cross)));
  EXPECT_NE(std::find(after.begin(), after.end(), Cell{20, 35}), after.end());
  EXPECT_EQ(service.path(local).cells, localBefore.cells);

  // Both doors shut: no path; reopening one re-queues the request and finds it again.
  service.setCell({20, 35}, false);
  service.tick();
  EXPECT_EQ(service.status(cross), PathStatus::NoPath);
  EXPECT_TRUE(service.path(cross).cells.empty());
  service.setCell({20, 5}, true);
  service.tick();
  ASSERT_EQ(service.status(cross), PathStatus::Ready);
  EXPECT_TRUE(validPath(m, service.path(cross)));
}

TEST_P(PathServiceTest, WithClearCacheOnCloseAHitIsWhatAFreshPlanGives) {
  // Zones keep a cache each, so a hit must equal planning on the same map: same cells and the
  // same expansion count charged to the budget, before and after a door closes.
  GridMap m = twoDoors();
  PathServiceConfig config;
  config.planner = GetParam();
  config.clear_cache_on_close = true;
  PathService service(m, config);
  GridPath first, hit;
  int expandedFirst = 0, expandedHit = 0;
  ASSERT_TRUE(service.solve({2, 30}, {38, 30}, first, expandedFirst));
  ASSERT_TRUE(service.solve({2, 30}, {38, 30}, hit, expandedHit));
  EXPECT_EQ(service.stats().planned, 1u);
  EXPECT_EQ(service.stats().cache_hits, 1u);
  EXPECT_EQ(hit.cells, first.cells);
  EXPECT_EQ(expandedHit, expandedFirst);
  EXPECT_GT(expandedFirst, 0);

  service.setCell({10, 10}, false);  // not on the path, yet the cache is cleared
  GridPath after;
  int expandedAfter = 0;
  ASSERT_TRUE(service.solve({2, 30}, {38, 30}, after, expandedAfter));
  EXPECT_EQ(service.stats().planned, 2u);
  GridMap same = m;
  PathService fresh(same, config);
  GridPath reference;
  int expandedReference = 0;
  ASSERT_TRUE(fresh.solve({2, 30}, {38, 30}, reference, expandedReference));
  EXPECT_EQ(after.cells, reference.cells);
  EXPECT_EQ(expandedAfter, expandedReference);
}

TEST_P(PathServiceTest, ReleasedHandlesGoStale) {
  GridMap m(16, 16);
  PathServiceConfig config;
  config.planner = GetParam();
  PathService service(m, config);
  PathRequestId a = service.request({0, 0}, {5, 5});
  service.release(a);
  PathRequestId b = service.request({1, 1}, {6, 6});
  EXPECT_EQ(a.slot, b.slot);
  service.tick();
  EXPECT_EQ(service.status(a), PathStatus::Unknown);
  EXPECT_EQ(service.status(b), PathStatus::Ready);
  EXPECT_EQ(service.stats().planned, 1u);
}

TEST_P(PathServiceTest, AuditMeasuresEveryPlanAgainstTheAStarOptimum) {
  GridMap m = test::randomMap(64, 64, 0.2, 5);
  PathServiceConfig config;
  config.planner = GetParam();
  config.paths_per_tick = 100;
  config.audit = true;
  PathService service(m, config);
  PathServiceConfig plain = config;
  plain.audit = false;
  PathService unaudited(m, plain);
  Pcg32 rng(5, 11);
  std::vector<PathRequestId> ids, plain_ids;
  for (int i = 0; i < 40; ++i) {
    const Cell a = test::randomFreeCell(m, rng), b = test::randomFreeCell(m, rng);
    ids.push_back(service.request(a, b));
    plain_ids.push_back(unaudited.request(a, b));
  }
  service.tick();
  unaudited.tick();
  std::uint64_t found = 0;
  double sum = 0, most = 0;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (service.status(ids[i]) != PathStatus::Ready) continue;
    const GridPath& p = service.path(ids[i]);
    // The audit changes no path.
    EXPECT_EQ(p.cells, unaudited.path(plain_ids[i]).cells) << i;
    const double optimum = test::referenceDistance(m, p.cells.front(), p.cells.back());
    if (!(optimum > 0)) continue;
    ++found;
    const double overhead = std::max(0.0, p.length / optimum - 1.0);
    sum += overhead;
    most = std::max(most, overhead);
  }
  const PathServiceStats s = service.stats();
  EXPECT_GT(found, 20u);
  EXPECT_EQ(s.audited, found);
  EXPECT_NEAR(s.overhead_sum, sum, 1e-9);
  EXPECT_NEAR(s.overhead_max, most, 1e-12);
  if (GetParam() == PlannerKind::AStar || GetParam() == PlannerKind::Jps) {
    EXPECT_EQ(s.overhead_max, 0.0) << "an optimal planner has no overhead";
  }
  EXPECT_EQ(unaudited.stats().audited, 0u);
  EXPECT_EQ(unaudited.stats().overhead_sum, 0.0);
}

class GridPlannerTest : public ::testing::TestWithParam<PlannerKind> {};

TEST_P(GridPlannerTest, WithLandmarksStaysOptimalAndRebuildsThemOnceTheMapChanged) {
  GridMap m = twoDoors();
  PathServiceConfig config;
  config.planner = GetParam();
  config.landmarks = 4;
  PathService service(m, config);
  const Cell from{2, 2}, to{38, 2};
  PathRequestId cross = service.request(from, to);
  service.tick();
  ASSERT_EQ(service.status(cross), PathStatus::Ready);
  EXPECT_NEAR(service.path(cross).length, test::referenceDistance(m, from, to), 1e-9);
  EXPECT_EQ(service.stats().landmark_builds, 0u);  // built with the service
  service.setCell({20, 5}, false);                 // the near door shuts: round by the far one
  service.setCell({30, 30}, false);                // and a second change in the same tick
  service.tick();
  ASSERT_EQ(service.status(cross), PathStatus::Ready);
  EXPECT_NEAR(service.path(cross).length, test::referenceDistance(m, from, to), 1e-9);
  EXPECT_TRUE(validPath(m, service.path(cross)));
  EXPECT_EQ(service.stats().landmark_builds, 1u);  // one rebuild for the tick's two changes
  service.setCell({20, 5}, true);
  PathRequestId again = service.request({3, 2}, to);
  service.tick();
  ASSERT_EQ(service.status(again), PathStatus::Ready);
  EXPECT_NEAR(service.path(again).length, test::referenceDistance(m, {3, 2}, to), 1e-9);
  EXPECT_EQ(service.stats().landmark_builds, 2u);
}

// HPA* answers these queries (ends under 64 cells apart) by its direct jump point search.
INSTANTIATE_TEST_SUITE_P(AStarJpsAndHpa, GridPlannerTest,
                         ::testing::Values(PlannerKind::AStar, PlannerKind::Jps, PlannerKind::Hpa),
                         [](const auto& info) {
                           return info.param == PlannerKind::AStar ? std::string("AStar")
                                  : info.param == PlannerKind::Jps ? std::string("Jps")
                                                                   : std::string("Hpa");
                         });

TEST(PathService, RefusesLandmarksForAPlannerThatTakesNone) {
  GridMap m = twoDoors();
  PathServiceConfig config;
  config.planner = PlannerKind::NavMesh;
  config.landmarks = 4;
  EXPECT_THROW(PathService(m, config), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Planners, PathServiceTest,
                         ::testing::Values(PlannerKind::AStar, PlannerKind::Hpa,
                                           PlannerKind::NavMesh, PlannerKind::Jps),
                         [](const auto& info) {
                           return info.param == PlannerKind::AStar ? std::string("AStar")
                                  : info.param == PlannerKind::Hpa ? std::string("Hpa")
                                  : info.param == PlannerKind::Jps ? std::string("Jps")
                                                                   : std::string("NavMesh");
                         });

}  // namespace
}  // namespace zonesim::ai
