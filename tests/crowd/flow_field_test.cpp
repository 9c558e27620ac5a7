// Flow fields: the integration field equals the A* optimum from every cell, following the
// direction field walks an optimal path, and agents released on a map with walls and random
// obstacles all reach their destinations without ever standing in a blocked cell. Two ranks
// stepping their halves with each other's agents as ghosts reproduce one rank bitwise. The
// lower bound that lets a crowd skip reading the distance never exceeds it, and a loaded
// field that breaks the bound gets none.

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "ai/grid_path.h"
#include "ai/grid_search.h"
#include "common/rng.h"
#include "crowd/flow_crowd.h"
#include "crowd_test_util.h"

namespace zonesim::crowd {
namespace {

// The zig-zag and 8% random blocks.
ai::GridMap obstacleMap() {
  ai::GridMap map = test::zigZagMap();
  Pcg32 rng(77, 1);
  for (int i = 0; i < 48 * 48 * 8 / 100; ++i) {
    int x = int(rng.next() % 48), y = int(rng.next() % 48);
    if (y != 2 && y != 45) map.setPassable(x, y, false);  // keep the goal rows open
  }
  map.setPassable(2, 2, true);
  map.setPassable(45, 45, true);
  return map;
}

TEST(FlowField, DistancesEqualAStarAndDirectionsFollowOptimalPaths) {
  ai::GridMap map = obstacleMap();
  FlowField field(map, ai::Cell{2, 2});
  ai::GridSearch search(map);
  ai::GridPath path;
  int checked = 0;
  for (int y = 0; y < 48; y += 3)
    for (int x = 0; x < 48; x += 3) {
      ai::Cell c{x, y};
      bool found = map.passable(x, y) && search.findPath(c, field.goal(), path);
      if (!found) {
        EXPECT_LT(field.distance(c), 0.0);
        continue;
      }
      EXPECT_NEAR(field.distance(c), path.length, 1e-4 * (1 + path.length));
      // Walk the direction field: a valid path of the same length.
      std::vector<ai::Cell> walk{c};
      ai::Cell at = c, next;
      while (field.next(at, next) && walk.size() < 10000) walk.push_back(at = next);
      ASSERT_EQ(walk.back(), field.goal());
      EXPECT_TRUE(ai::isValidPath(map, walk));
      EXPECT_NEAR(ai::pathLength(walk), path.length, 1e-9 * (1 + path.length));
      ++checked;
    }
  EXPECT_GT(checked, 150);
}

TEST(FlowField, LowerBoundNeverExceedsTheDistanceAndLoadedFieldsThatBreakItGetNone) {
  ai::GridMap map = obstacleMap();
  const FlowField field(map, ai::Cell{2, 2});
  int withNext = 0, positive = 0;
  ai::Cell broken{-1, -1}, next;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      const ai::Cell c{x, y};
      if (!field.next(c, next)) continue;
      ++withNext;
      EXPECT_LE(field.nextCellLowerBound(c), field.distance(c)) << x << "," << y;
      positive += field.nextCellLowerBound(c) > 0;
      if (x == 40 && broken.x < 0) broken = c;
    }
  EXPECT_GT(withNext, 1000);
  EXPECT_EQ(positive, withNext);  // every cell with a next cell is off the goal
  ASSERT_GE(broken.x, 0);
  // The same fields as if loaded from a file, but one distance shorter than any path.
  std::vector<float> distance = field.distances();
  distance[std::size_t(broken.y) * 48 + std::size_t(broken.x)] = 1.0f;
  const FlowField loaded(map, field.goal(), distance, field.directions());
  EXPECT_EQ(loaded.nextCellLowerBound(broken), 0.0);
  EXPECT_EQ(loaded.nextCellLowerBound(ai::Cell{40, 40}), 0.0);
  const FlowField intact(map, field.goal(), field.distances(), field.directions());
  EXPECT_EQ(intact.nextCellLowerBound(broken), field.nextCellLowerBound(broken));
}

TEST(FlowCrowd, AllAgentsReachTheirDestination) {
  ai::GridMap map = obstacleMap();
  MapFrame frame{Vec2{-24.0, -24.0}, 1.0};
  FlowCrowd crowd(map, frame, FlowCrowdSettings{});
  int a = crowd.addDestination(ai::Cell{2, 2});
  int b = crowd.addDestination(ai::Cell{45, 45});
  test::AgentArrays agents;
  std::vector<std::uint16_t> dest;
  std::vector<std::uint8_t> arrived;
  Pcg32 rng(5, 5);
  double longest = 0;
  while (agents.ids.size() < 400) {
    Vec2 p{rng.uniform(-24, 24), rng.uniform(-24, 24)};
    ai::Cell c = frame.cellOf(p);
    int d = agents.ids.size() % 2 ? a : b;
    if (!map.passable(c.x, c.y) || crowd.field(d).distance(c) < 0) continue;
    longest = std::max(longest, crowd.field(d).distance(c));
    agents.add(agents.ids.size() + 1, p, Vec2{});
    dest.push_back(std::uint16_t(d));
    arrived.push_back(0);
  }
  const double dt = 1.0 / 20;
  // Generous bound: the longest path at a quarter of the top speed.
  const int max_steps = int(longest / (0.25 * crowd.settings().max_speed) / dt);
  int reached = 0, steps = 0, blockedVisits = 0;
  while (!agents.ids.empty() && steps < max_steps) {
    crowd.step(agents.span(), dest, arrived, {}, dt);
    ++steps;
    // Arrived agents leave the scene (as at an exit), compacting the arrays.
    std::size_t w = 0;
    for (std::size_t i = 0; i < agents.ids.size(); ++i) {
      if (!walkable(map, frame, agents.pos[i])) ++blockedVisits;
      if (arrived[i]) {
        ++reached;
        continue;
      }
      agents.ids[w] = agents.ids[i];
      agents.pos[w] = agents.pos[i];
      agents.vel[w] = agents.vel[i];
      dest[w] = dest[i];
      arrived[w] = 0;
      ++w;
    }
    agents.ids.resize(w);
    agents.pos.resize(w);
    agents.vel.resize(w);
    dest.resize(w);
    arrived.resize(w);
  }
  std::printf("%d agents arrived in %.1f s (bound %.1f s)\n", reached, steps * dt, max_steps * dt);
  EXPECT_EQ(reached, 400);
  EXPECT_TRUE(agents.ids.empty());
  EXPECT_EQ(blockedVisits, 0);
}

TEST(FlowCrowd, FieldsAreRebuiltWhenADoorCloses) {
  ai::GridMap map(20, 5);
  for (int y = 0; y < 5; ++y) map.setPassable(10, y, y == 2);  // a wall with one door
  FlowCrowd crowd(map, MapFrame{}, FlowCrowdSettings{});
  int d = crowd.addDestination(ai::Cell{18, 2});
  EXPECT_NEAR(crowd.field(d).distance(ai::Cell{1, 2}), 17.0, 1e-6);
  EXPECT_EQ(crowd.refreshFields(), 0);
  map.setPassable(10, 2, false);
  EXPECT_EQ(crowd.refreshFields(), 1);
  EXPECT_LT(crowd.field(d).distance(ai::Cell{1, 2}), 0.0);
}

}  // namespace
}  // namespace zonesim::crowd

namespace zonesim::crowd {
namespace {

struct FlowAgents {
  test::AgentArrays a;
  std::vector<std::uint16_t> dest;
  std::vector<std::uint8_t> arrived;
  void add(const FlowAgents& from, std::size_t i) {
    a.add(from.a.ids[i], from.a.pos[i], from.a.vel[i]);
    dest.push_back(from.dest[i]);
    arrived.push_back(from.arrived[i]);
  }
  // Agents still in the crowd, as ghosts for another rank (arrived ones are not seen).
  test::AgentArrays activeGhosts() const {
    test::AgentArrays g;
    for (std::size_t i = 0; i < a.ids.size(); ++i)
      if (!arrived[i]) g.add(a.ids[i], a.pos[i], a.vel[i]);
    return g;
  }
};

TEST(FlowCrowd, TwoRanksWithGhostsMatchOneRankBitwise) {
  ai::GridMap map = obstacleMap();
  MapFrame frame{Vec2{-24.0, -24.0}, 1.0};
  FlowCrowd one(map, frame, FlowCrowdSettings{}), left(map, frame, FlowCrowdSettings{}),
      right(map, frame, FlowCrowdSettings{});
  for (FlowCrowd* c : {&one, &left, &right}) {
    c->addDestination(ai::Cell{2, 2});
    c->addDestination(ai::Cell{45, 45});
  }
  FlowAgents whole;
  Pcg32 rng(8, 8);
  while (whole.a.ids.size() < 600) {
    Vec2 p{rng.uniform(-24, 24), rng.uniform(-24, 24)};
    std::uint16_t d = std::uint16_t(rng.next() % 2);
    if (one.field(d).distance(frame.cellOf(p)) < 0) continue;
    whole.a.add(rng.next() * 977ULL + whole.a.ids.size(), p, Vec2{});
    whole.dest.push_back(d);
    whole.arrived.push_back(0);
  }
  FlowAgents split = whole;
  const double dt = 1.0 / 20;
  for (int s = 0; s < 300; ++s) {
    one.step(whole.a.span(), whole.dest, whole.arrived, {}, dt);
    // Re-split by position every step (agents migrate), the right part stored reversed.
    FlowAgents l, r;
    for (std::size_t i = 0; i < split.a.ids.size(); ++i)
      (split.a.pos[i].x < 0 ? l : r).add(split, i);
    std::reverse(r.a.ids.begin(), r.a.ids.end());
    std::reverse(r.a.pos.begin(), r.a.pos.end());
    std::reverse(r.a.vel.begin(), r.a.vel.end());
    std::reverse(r.dest.begin(), r.dest.end());
    std::reverse(r.arrived.begin(), r.arrived.end());
    test::AgentArrays lGhosts = r.activeGhosts(), rGhosts = l.activeGhosts();
    left.step(l.a.span(), l.dest, l.arrived, lGhosts.ghosts(), dt);
    right.step(r.a.span(), r.dest, r.arrived, rGhosts.ghosts(), dt);
    split = FlowAgents{};
    for (FlowAgents* part : {&l, &r})
      for (std::size_t i = 0; i < part->a.ids.size(); ++i) split.add(*part, i);
  }
  std::map<std::uint64_t, std::tuple<Vec2, Vec2, int>> a, b;
  int arrivedCount = 0;
  for (std::size_t i = 0; i < whole.a.ids.size(); ++i) {
    a[whole.a.ids[i]] = {whole.a.pos[i], whole.a.vel[i], whole.arrived[i]};
    arrivedCount += whole.arrived[i];
  }
  for (std::size_t i = 0; i < split.a.ids.size(); ++i)
    b[split.a.ids[i]] = {split.a.pos[i], split.a.vel[i], split.arrived[i]};
  EXPECT_GT(arrivedCount, 0);  // arrivals happened during the comparison
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace zonesim::crowd
