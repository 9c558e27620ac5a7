// Level of detail: levels follow the distance to the nearest player, each level is updated
// once per its period with the skipped time caught up (every agent's clock stays exact), and
// a flow crowd planned with LOD still brings every agent to its destination, arriving close
// to the full-detail times.

#include "crowd/lod.h"

#include <gtest/gtest.h>

#include <map>

#include "common/rng.h"
#include "crowd/flock.h"
#include "crowd/flow_crowd.h"
#include "crowd_test_util.h"

namespace zonesim::crowd {
namespace {

TEST(Lod, LevelsPeriodsAndCaughtUpTime) {
  LodSettings s;
  s.near_radius = 10;
  s.far_radius = 30;
  s.mid_every = 3;
  s.far_every = 8;
  LevelOfDetail lod(s);
  std::vector<std::uint64_t> ids;
  std::vector<Vec2> pos;
  for (int i = 0; i < 300; ++i) {
    ids.push_back(std::uint64_t(i) * 7919 + 3);
    pos.push_back(Vec2{0.2 * i, 0.0});  // 0 .. 60 m from the player at the origin
  }
  std::vector<Vec2> players{{0, 0}, {-500, 0}};
  std::vector<std::int64_t> last(ids.size(), -1);
  std::vector<double> advanced(ids.size(), 0.0);
  std::vector<int> updates(ids.size(), 0);
  const double dt = 0.05;
  const int ticks = 240;  // a multiple of every period
  for (int t = 0; t < ticks; ++t) {
    StepPlan plan = lod.plan(ids, pos, players, t, dt, last);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      advanced[i] += plan.dt[i];
      updates[i] += plan.dt[i] > 0;
    }
  }
  for (std::size_t i = 0; i < ids.size(); ++i) {
    double d = pos[i].x;
    LodLevel expect = d <= 10 ? LodLevel::Near : (d <= 30 ? LodLevel::Mid : LodLevel::Far);
    ASSERT_EQ(lod.level(i), expect) << i;
    int every = d <= 10 ? 1 : (d <= 30 ? 3 : 8);
    // First update on tick 0 (new agent), then once per period.
    EXPECT_NEAR(updates[i], 1 + (ticks - 1) / every, 1) << i;
    // Time advanced up to the agent's last update equals (last + 1) ticks exactly.
    EXPECT_NEAR(advanced[i], double(last[i] + 1) * dt, 1e-9) << i;
    EXPECT_GT(last[i], ticks - 1 - every);
  }
  EXPECT_EQ(lod.levelCounts()[0] + lod.levelCounts()[1] + lod.levelCounts()[2], ids.size());
}

TEST(Lod, FlowCrowdWithLodReachesTheSameOutcome) {
  ai::GridMap map(80, 80);
  for (int y = 10; y < 70; ++y) map.setPassable(40, y, false);
  MapFrame frame{};
  const Vec2 player{20, 20};
  struct Run {
    std::map<std::uint64_t, int> arrivalTick;
    std::size_t updates = 0;
  };
  auto run = [&](bool useLod) {
    FlowCrowd crowd(map, frame, FlowCrowdSettings{});
    crowd.addDestination(ai::Cell{70, 40});
    test::AgentArrays a;
    Pcg32 rng(3, 3);
    while (a.ids.size() < 200) {
      Vec2 p{rng.uniform(1, 39), rng.uniform(1, 79)};
      a.add(a.ids.size() + 1, p, Vec2{});
    }
    std::vector<std::uint16_t> dest(a.ids.size(), 0);
    std::vector<std::uint8_t> arrived(a.ids.size(), 0);
    std::vector<std::int64_t> last(a.ids.size(), -1);
    LodSettings s;
    s.near_radius = 15;
    s.far_radius = 30;
    s.mid_every = 2;
    s.far_every = 6;
    LevelOfDetail lod(s);
    Run r;
    const double dt = 0.05;
    for (int t = 0; t < 4000 && r.arrivalTick.size() < a.ids.size(); ++t) {
      StepPlan plan;
      if (useLod) {
        plan = lod.plan(a.ids, a.pos, std::span<const Vec2>(&player, 1), t, dt, last);
        r.updates += lod.updated();
      } else {
        r.updates += a.ids.size();
      }
      crowd.step(a.span(), dest, arrived, {}, dt, plan);
      for (std::size_t i = 0; i < a.ids.size(); ++i)
        if (arrived[i]) r.arrivalTick.emplace(a.ids[i], t);
      for (Vec2 p : a.pos) EXPECT_TRUE(walkable(map, frame, p));
    }
    return r;
  };
  Run full = run(false), cheap = run(true);
  ASSERT_EQ(full.arrivalTick.size(), 200u);
  ASSERT_EQ(cheap.arrivalTick.size(), 200u);
  double sumDiff = 0, maxDiff = 0, sumTime = 0;
  for (auto [id, t] : full.arrivalTick) {
    double diff = std::abs(cheap.arrivalTick[id] - t) * 0.05;
    sumDiff += diff;
    maxDiff = std::max(maxDiff, diff);
    sumTime += t * 0.05;
  }
  std::printf(
      "updates %zu vs %zu (%.2fx fewer); arrival time mean %.1f s, |diff| mean %.2f s "
      "max %.2f s\n",
      cheap.updates, full.updates, double(full.updates) / cheap.updates, sumTime / 200,
      sumDiff / 200, maxDiff);
  EXPECT_LT(cheap.updates, full.updates);
  // Same outcome: every agent arrives, on average within 5% of its full-detail arrival time.
  EXPECT_LT(sumDiff / sumTime, 0.05);
}

TEST(Lod, FlockFollowsThePlan) {
  // Three agents close together: one skipped (dt 0), one cheap (no neighbours, goal only),
  // one at full detail with a double step.
  test::AgentArrays a;
  a.add(1, Vec2{0, 0}, Vec2{0.5, 0});
  a.add(2, Vec2{0.5, 0}, Vec2{0, 0.5});
  a.add(3, Vec2{0, 0.5}, Vec2{-0.5, 0});
  const test::AgentArrays before = a;
  std::vector<Vec2> goal(3, Vec2{1.0, 0.0});
  std::vector<double> dt{0.0, 0.1, 0.2};
  std::vector<std::uint8_t> steer{1, 0, 1};
  FlockSettings s;
  Flock flock(s);
  flock.step(a.span(), {}, 0.05, goal, StepPlan{dt, steer});
  EXPECT_EQ(a.pos[0], before.pos[0]);
  EXPECT_EQ(a.vel[0], before.vel[0]);
  // Cheap update: v += goal_weight (goal - v) h, then x += v h, with no neighbour terms.
  Vec2 v1 = before.vel[1] + (goal[1] - before.vel[1]) * (s.goal_weight * 0.1);
  EXPECT_NEAR(a.vel[1].x, v1.x, 1e-15);
  EXPECT_NEAR(a.vel[1].y, v1.y, 1e-15);
  EXPECT_NEAR(a.pos[1].x, before.pos[1].x + v1.x * 0.1, 1e-15);
  EXPECT_NEAR(a.pos[1].y, before.pos[1].y + v1.y * 0.1, 1e-15);
  // Full detail: the skipped agent still pushes it (separation), so it differs from the
  // goal-only update.
  Vec2 v2goal = before.vel[2] + (goal[2] - before.vel[2]) * (s.goal_weight * 0.2);
  EXPECT_GT(length(a.vel[2] - v2goal), 0.1);
  EXPECT_NEAR(a.pos[2].x, before.pos[2].x + a.vel[2].x * 0.2, 1e-15);
}

TEST(Lod, CrowdingCountsEachCellOnceWithGhostsAndTheMask) {
  // Cells of 2 m: (0,0) holds agents 0, 1 and a ghost; (1,0) agent 2 (not counted) and 3;
  // (-1,-1) agent 4 alone.
  const std::vector<Vec2> agents{{0.5, 0.5}, {1.9, 1.0}, {2.0, 0.1}, {3.5, 1.5}, {-0.1, -0.1}};
  const std::vector<std::uint8_t> counted{1, 1, 0, 1, 1};
  const std::vector<Vec2> ghosts{{1.0, 1.99}, {9.0, 9.0}};
  std::vector<std::uint32_t> out;
  crowdingCounts(agents, counted, ghosts, 2.0, out);
  EXPECT_EQ(out, (std::vector<std::uint32_t>{3, 3, 1, 1, 1}));
  crowdingCounts(agents, {}, {}, 2.0, out);  // everyone counted, no ghosts
  EXPECT_EQ(out, (std::vector<std::uint32_t>{2, 2, 2, 2, 1}));
  // Points thousands of cells apart take the sparse path: the same answer.
  const std::vector<Vec2> spread{{0.5, 0.5}, {1e6, 1e6}, {1e6 + 0.5, 1e6}, {-1e6, 3.0}};
  crowdingCounts(spread, {}, {}, 2.0, out);
  EXPECT_EQ(out, (std::vector<std::uint32_t>{1, 2, 2, 1}));
  EXPECT_THROW(crowdingCounts(agents, counted, ghosts, 0.0, out), std::invalid_argument);
  EXPECT_THROW(crowdingCounts(agents, std::vector<std::uint8_t>{1}, {}, 2.0, out),
               std::invalid_argument);
}

TEST(Lod, CrowdedAgentsArePlannedNearWhereverTheyAre) {
  LodSettings s;  // no player: everyone far, every 8 ticks, without steering
  s.crowded_count = 3;
  LevelOfDetail lod(s);
  const std::vector<std::uint64_t> ids{1, 2, 3, 4};
  const std::vector<Vec2> pos{{0, 0}, {0.5, 0}, {1, 0}, {50, 50}};
  const std::vector<std::uint32_t> crowding{3, 3, 3, 1};
  for (int t = 0; t < 8; ++t) {
    const StepPlan plan = lod.plan(ids, pos, {}, t, 0.05, {}, crowding);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(lod.level(i), LodLevel::Near);
      EXPECT_DOUBLE_EQ(plan.dt[i], 0.05);
      EXPECT_EQ(plan.steer[i], 1);
    }
    EXPECT_EQ(lod.level(3), LodLevel::Far);
  }
  // Without the counts (or with crowded_count 0) the same agents stay far.
  lod.plan(ids, pos, {}, 0, 0.05);
  EXPECT_EQ(lod.level(0), LodLevel::Far);
  EXPECT_THROW(lod.plan(ids, pos, {}, 0, 0.05, {}, std::vector<std::uint32_t>{1}),
               std::invalid_argument);
  LodSettings bad;
  bad.crowded_cell = 0;
  EXPECT_THROW(LevelOfDetail{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace zonesim::crowd
