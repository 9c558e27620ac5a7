// scenes/roads.yaml stepped by the zone's RoadMovement: every edge an NPC takes exists in its
// direction, is open and is one it may use, and every trip costs what Floyd-Warshall (an
// independent all-pairs reference) says the cheapest way costs.

#include "zone_node/systems/road_movement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "common/scene.h"
#include "zone_node/zone_fixture.h"
#include "zone_node/population.h"
#include "zone_node/systems/lone_zone.h"

namespace zonesim::zone {
namespace {

using Matrix = std::vector<std::vector<double>>;
constexpr double kNone = std::numeric_limits<double>::infinity();

bool shut(const NpcRoads& r, std::size_t edge, double t) {
  for (const NpcRoads::Closure& c : r.closures)
    if (std::size_t(c.edge) == edge && t >= c.from && t < c.until) return true;
  return false;
}

/// Cost of the edge a -> b an NPC of `r` may take at time t (kNone if none).
double edgeCost(const NpcRoads& r, int a, int b, double t) {
  double best = kNone;
  for (std::size_t k = 0; k < r.edges.size(); ++k) {
    const NpcRoads::Edge& e = r.edges[k];
    const bool forward = e.a == a && e.b == b, back = !e.one_way && e.a == b && e.b == a;
    if ((forward || back) && (e.flags & ~r.may_use) == 0 && !shut(r, k, t))
      best = std::min(best, e.cost);
  }
  return best;
}

Matrix floydWarshall(const NpcRoads& r, double t) {
  const int n = int(r.nodes.size());
  Matrix d(std::size_t(n), std::vector<double>(std::size_t(n), kNone));
  for (int a = 0; a < n; ++a) {
    d[a][a] = 0;
    for (int b = 0; b < n; ++b)
      if (a != b) d[a][b] = edgeCost(r, a, b, t);
  }
  for (int k = 0; k < n; ++k)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) d[a][b] = std::min(d[a][b], d[a][k] + d[k][b]);
  return d;
}

TEST(RoadMovement, NpcsTakeOnlyOpenAllowedEdgesAndCheapestPaths) {
  Scene scene = loadScene(std::string(ZONESIM_SOURCE_DIR) + "/scenes/roads.yaml");
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  RoadMovement roads(scene.npcs);
  ASSERT_TRUE(roads.active());
  struct Trip {
    int from = -1;
    double cost = 0, started = 0;
  };
  std::vector<Trip> trips(store.size());
  // Each NPC starts on a node that is its first goal, so its first draw opens its first trip.
  for (std::size_t i = 0; i < store.size(); ++i)
    trips[i].from = std::get<RoadTripData>(store.npc[i].crowd).next_node;
  std::vector<std::vector<Matrix>> best(scene.npcs.size());  // [population][shut?]
  for (std::size_t p = 0; p < scene.npcs.size(); ++p)
    best[p] = {floydWarshall(scene.npcs[p].roads, 0), floydWarshall(scene.npcs[p].roads, 20)};
  const double dt = scene.dt;
  int decisions = 0, wrong_edges = 0, trips_checked = 0, trips_off = 0, door_uses = 0;
  int closed_uses = 0, waits = 0;
  double worst = 0;
  for (std::uint64_t tick = 0; tick < 7200; ++tick) {
    const double t = double(tick) * dt;
    std::vector<int> before(store.size()), goal_before(store.size());
    for (std::size_t i = 0; i < store.size(); ++i) {
      before[i] = std::get<RoadTripData>(store.npc[i].crowd).next_node;
      goal_before[i] = std::get<RoadTripData>(store.npc[i].crowd).goal;
    }
    LoneZone{dt}.step(roads, store, tick);
    for (std::size_t i = 0; i < store.size(); ++i) {
      const NpcData& npc = store.npc[i];
      const NpcRoads& r = scene.npcs[std::size_t(npc.population)].roads;
      Trip& trip = trips[i];
      if (goal_before[i] != std::get<RoadTripData>(npc.crowd).goal) {
        // It stood on its goal and drew the next: that trip ended here. Trips that saw one
        // state of the closure (before, during or after its 10-30 s) are compared.
        auto phase = [](double s) { return s < 10 ? 0 : s < 30 ? 1 : 2; };
        if (trip.cost > 0 && phase(trip.started) == phase(t)) {
          const Matrix& d = best[std::size_t(npc.population)][phase(t) == 1 ? 1 : 0];
          const double opt = d[std::size_t(trip.from)][std::size_t(goal_before[i])];
          worst = std::max(worst, std::abs(trip.cost - opt));
          trips_off += std::abs(trip.cost - opt) > 1e-9;
          ++trips_checked;
        }
        trip = {goal_before[i], 0, t};
      }
      if (std::get<RoadTripData>(npc.crowd).next_node == before[i]) {
        waits += (store.vel[i].norm() == 0 && before[i] != std::get<RoadTripData>(npc.crowd).goal);
        continue;
      }
      // A decision at node before[i] (one per tick here: edges are far longer than a step).
      ++decisions;
      const double c = edgeCost(r, before[i], std::get<RoadTripData>(npc.crowd).next_node, t);
      wrong_edges += c == kNone;
      for (std::size_t k = 0; k < r.edges.size(); ++k) {
        const NpcRoads::Edge& e = r.edges[k];
        const bool on = (e.a == before[i] && e.b == std::get<RoadTripData>(npc.crowd).next_node) ||
                        (e.b == before[i] && e.a == std::get<RoadTripData>(npc.crowd).next_node);
        if (on && e.flags) ++door_uses;
        if (on && shut(r, k, t)) ++closed_uses;
      }
      trip.cost += c;
    }
  }
  std::printf(
      "120 s, %zu NPCs: %d decisions, %d on edges that do not exist or may not be used,"
      " %d through the door, %d onto a shut edge, %d NPC-ticks waiting; %d trips"
      " checked, %d not cheapest (worst difference %.3g)\n",
      store.size(), decisions, wrong_edges, door_uses, closed_uses, waits, trips_checked, trips_off,
      worst);
  EXPECT_GT(decisions, 1000);
  EXPECT_EQ(wrong_edges, 0);
  EXPECT_EQ(closed_uses, 0);
  EXPECT_GT(door_uses, 0);  // pedestrians do use it
  EXPECT_GT(trips_checked, 200);
  EXPECT_EQ(trips_off, 0);
}

TEST(RoadMovement, SceneMistakesNameTheirLine) {
  auto fails = [](const std::string& roads, const std::string& expect) {
    testing::expectSceneError(
        testing::withSmallWorld("populations:\n  - kind: npc\n    count: 2\n    roads: " + roads +
                                "\n"),
        expect);
  };
  const std::string two = "nodes: [[10, 0, 10], [20, 0, 10]]";
  fails("{" + two + ", edges: [[0, 0]]}",
        "t.yaml:8: populations[0].roads.edges[0]: an edge needs two different nodes");
  fails("{" + two + ", edges: [[0, 2]]}", "populations[0].roads.edges[0][1]");
  fails("{" + two + ", edges: [{a: 0, b: 1, one_way: true}]}", "node 1 cannot reach node 0");
  fails("{" + two + ", edges: [{a: 0, b: 1, flags: [door]}]}", "over the edges these NPCs may use");
  fails("{" + two + ", edges: [[0, 1]], may_use: [ladder]}", "no edge has the flag 'ladder'");
  fails("{" + two + ", edges: [[0, 1]], closures: [{edge: 0, from: 5, until: 5}]}", "until");
}

}  // namespace
}  // namespace zonesim::zone
