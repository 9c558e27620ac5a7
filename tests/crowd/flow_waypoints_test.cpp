// Flow crowds on a navigation mesh (crowd/flow_waypoints.h): in an open room every cell aims
// straight at the goal; on a map of walls every aim is in sight of its cell's centre and no
// nearer the goal in a straight line than the cell could walk; and a crowd aiming at the
// funnelled path's corners reaches its goals without entering a blocked cell, sooner than the
// same crowd on the grid field's octile paths.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ai/navmesh.h"
#include "common/rng.h"
#include "crowd/flow_crowd.h"
#include "crowd/flow_waypoints.h"
#include "crowd/map_frame.h"
#include "crowd_test_util.h"

namespace zonesim::crowd {
namespace {

// The zig-zag and a few pillars.
ai::GridMap wallsMap() {
  ai::GridMap map = test::zigZagMap();
  for (int k = 0; k < 6; ++k) {
    map.setPassable(6 + 7 * k, 8, false);
    map.setPassable(4 + 7 * k, 24, false);
    map.setPassable(9 + 6 * k, 40, false);
  }
  return map;
}

// Distance from `p` to the nearest blocked cell of `map`.
double clearance(const ai::GridMap& map, Vec2 p) {
  double best = 1e300;
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x) {
      if (map.passable(x, y)) continue;
      const double dx = std::max({x - p.x, 0.0, p.x - (x + 1)});
      const double dy = std::max({y - p.y, 0.0, p.y - (y + 1)});
      best = std::min(best, std::hypot(dx, dy));
    }
  return best;
}

TEST(FlowWaypoints, AnOpenRoomAimsEveryCellStraightAtTheGoal) {
  const ai::GridMap map(20, 12);
  const ai::NavMesh mesh(map, ai::NavMeshConfig{});
  const std::vector<float> aims = navMeshWaypoints(mesh, FlowField(map, ai::Cell{3, 4}));
  ASSERT_EQ(aims.size(), 2u * 20 * 12);
  for (std::size_t k = 0; k < aims.size(); k += 2) {
    EXPECT_EQ(aims[k], 3.5f);
    EXPECT_EQ(aims[k + 1], 4.5f);
  }
}

TEST(FlowWaypoints, EveryAimIsInSightOfItsCellOnAMapOfWalls) {
  const ai::GridMap map = wallsMap();
  const ai::NavMesh mesh(map, ai::NavMeshConfig{});
  const ai::Cell goal{2, 2};
  const std::vector<float> aims = navMeshWaypoints(mesh, FlowField(map, goal), 0.4, &map);
  const MapFrame frame{};  // map units as metres
  int with = 0, corners = 0, blind = 0, touches = 0, far_enough = 0, moved = 0;
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x) {
      const std::size_t at = 2 * std::size_t(y * map.width() + x);
      ASSERT_EQ(std::isnan(aims[at]), mesh.polygonAt(x, y) < 0) << x << ", " << y;
      if (std::isnan(aims[at])) continue;
      ++with;
      const Vec2 from{x + 0.5, y + 0.5}, aim{aims[at], aims[at + 1]};
      // The grid's exact sight test calls a segment touching a wall's corner blocked; the
      // funnel's straight path may touch one. Such a segment is clear when nudged one way.
      if (!lineOfSight(map, frame, from, aim)) {
        const Vec2 d = aim - from, side = Vec2{-d.y, d.x} * (1e-6 / length(d));
        const bool touch = lineOfSight(map, frame, from + side, aim + side) ||
                           lineOfSight(map, frame, from - side, aim - side);
        touches += touch;
        blind += !touch;
      }
      // A corner moved off the wall's end keeps the clearance from every blocked cell.
      const bool at_goal = aim.x == goal.x + 0.5 && aim.y == goal.y + 0.5;
      corners += !at_goal;
      if (!at_goal && aim.x != std::floor(aim.x)) {  // off the lattice: moved off a wall's end
        ++moved;
        far_enough += clearance(map, aim) >= 0.4 - 1e-9;
      }
    }
  std::printf("%d cells on the mesh, %d aim at a corner before the goal, %d of them moved off "
              "a wall's end; %d aims touch a wall's corner\n",
              with, corners, moved, touches);
  EXPECT_GT(with, 1500);
  EXPECT_GT(corners, 1000);  // two walls between most cells and the goal
  EXPECT_EQ(blind, 0);
  EXPECT_GT(moved, corners / 2);
  EXPECT_EQ(far_enough, moved);
}

TEST(FlowWaypoints, AGoalOffTheMeshIsRefusedByName) {
  const ai::GridMap map(10, 10);
  const ai::NavMesh mesh(map, {ai::NavBox{4.5, 5.5, 6.0, 7.0}}, ai::NavMeshConfig{});
  try {
    navMeshWaypoints(mesh, FlowField(map, ai::Cell{5, 6}));
    FAIL() << "a goal under a static box is off the mesh";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "navmesh flow: goal cell (5, 6) is off the mesh");
  }
}

struct CrowdRun {
  int arrived = 0;
  int blocked_visits = 0;
  double mean_arrival_s = 0;
  double last_arrival_s = 0;
};

CrowdRun walk(bool navmesh, std::size_t count) {
  const ai::GridMap map = wallsMap();
  const MapFrame frame{Vec2{-24.0, -24.0}, 1.0};
  FlowCrowdSettings s;
  s.navmesh = navmesh;
  s.navmesh_config.agent_radius = 0.4;
  FlowCrowd crowd(map, frame, s);
  const int a = crowd.addDestination(ai::Cell{2, 2});
  const int b = crowd.addDestination(ai::Cell{45, 45});
  test::AgentArrays agents;
  std::vector<std::uint16_t> dest;
  std::vector<std::uint8_t> arrived;
  Pcg32 rng(5, 5);
  while (agents.ids.size() < count) {
    const Vec2 p{rng.uniform(-24, 24), rng.uniform(-24, 24)};
    const ai::Cell c = frame.cellOf(p);
    const int d = agents.ids.size() % 2 ? a : b;
    if (!map.passable(c.x, c.y) || crowd.field(d).distance(c) < 0) continue;
    agents.add(agents.ids.size() + 1, p, Vec2{});
    dest.push_back(std::uint16_t(d));
    arrived.push_back(0);
  }
  const double dt = 1.0 / 20;
  CrowdRun r;
  double arrival_sum = 0;
  for (int step = 1; step <= 4000 && r.arrived < int(count); ++step) {
    crowd.step(agents.span(), dest, arrived, {}, dt);
    for (std::size_t i = 0; i < agents.ids.size(); ++i) {
      r.blocked_visits += !arrived[i] && !walkable(map, frame, agents.pos[i]);
      if (arrived[i] == 1) {  // counted once, then parked as arrived (2)
        arrived[i] = 2;
        ++r.arrived;
        arrival_sum += step * dt;
        r.last_arrival_s = step * dt;
      }
    }
  }
  r.mean_arrival_s = r.arrived ? arrival_sum / r.arrived : 0;
  return r;
}

TEST(FlowCrowd, OnANavMeshAgentsArriveSoonerThanOnTheGridField) {
  for (std::size_t count : {30u, 300u}) {
    const CrowdRun grid = walk(false, count), mesh = walk(true, count);
    std::printf("%zu agents: grid field: mean %.2f s, last %.2f s; navmesh: mean %.2f s, last %.2f s\n",
                count, grid.mean_arrival_s, grid.last_arrival_s, mesh.mean_arrival_s,
                mesh.last_arrival_s);
    EXPECT_EQ(grid.arrived, int(count));
    EXPECT_EQ(mesh.arrived, int(count));
    EXPECT_EQ(mesh.blocked_visits, 0);
    EXPECT_LT(mesh.mean_arrival_s, grid.mean_arrival_s);
  }
}

}  // namespace
}  // namespace zonesim::crowd
