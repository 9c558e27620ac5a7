// Waypoint graphs: cheapest paths with weights, flags and shut doors, and A* equal to a
// zero-heuristic search on random graphs whose weights undercut the straight-line distance.

#include "ai/waypoint_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/rng.h"

namespace zonesim::ai {
namespace {

constexpr std::uint32_t kDoor = 1, kWater = 2;

// A square a-b-c-d: the short way a->b->c runs through a door and water; the long way a->d->c
// is dry.
struct Square {
  WaypointGraph g;
  int a, b, c, d, ab, bc;
  Square() {
    a = g.addNode({0, 0});
    b = g.addNode({10, 0});
    c = g.addNode({10, 10});
    d = g.addNode({0, 10});
    ab = g.addEdge(a, b, 10, kDoor);
    bc = g.addEdge(b, c, 10, kWater);
    g.addEdge(a, d, 15);
    g.addEdge(d, c, 15);
  }
};

TEST(WaypointGraph, FlagsDecideWhichEdgesAnAgentMayUse) {
  Square s;
  WaypointPath path;
  ASSERT_TRUE(s.g.findPath(s.a, s.c, kDoor | kWater, path));
  EXPECT_EQ(path.nodes, (std::vector<int>{s.a, s.b, s.c}));
  EXPECT_DOUBLE_EQ(path.cost, 20.0);
  ASSERT_TRUE(s.g.findPath(s.a, s.c, kDoor, path));
  EXPECT_EQ(path.nodes, (std::vector<int>{s.a, s.d, s.c}));
  EXPECT_DOUBLE_EQ(path.cost, 30.0);
  ASSERT_TRUE(s.g.findPath(s.a, s.b, kDoor, path));
  // Without the door flag b is only reachable across the water.
  EXPECT_FALSE(s.g.findPath(s.a, s.b, 0, path));
}

TEST(WaypointGraph, ShutDoorsAndOneWayEdges) {
  Square s;
  WaypointPath path;
  s.g.setEdgeOpen(s.ab, false);
  ASSERT_TRUE(s.g.findPath(s.a, s.c, kDoor | kWater, path));
  EXPECT_DOUBLE_EQ(path.cost, 30.0);
  s.g.setEdgeOpen(s.ab, true);
  ASSERT_TRUE(s.g.findPath(s.a, s.c, kDoor | kWater, path));
  EXPECT_DOUBLE_EQ(path.cost, 20.0);

  WaypointGraph g;
  int x = g.addNode({0, 0}), y = g.addNode({1, 0});
  g.addEdge(x, y, 1.0, 0, false);
  EXPECT_TRUE(g.findPath(x, y, 0, path));
  EXPECT_FALSE(g.findPath(y, x, 0, path));
  EXPECT_TRUE(path.nodes.empty());
  EXPECT_EQ(g.edgeCount(), 1);
}

// Plain Dijkstra over the same edges for comparison.
double dijkstra(const std::vector<std::tuple<int, int, double>>& edges, int n, int s, int t) {
  std::vector<double> dist(std::size_t(n), std::numeric_limits<double>::infinity());
  std::vector<bool> done(std::size_t(n), false);
  dist[std::size_t(s)] = 0;
  for (int it = 0; it < n; ++it) {
    int u = -1;
    for (int i = 0; i < n; ++i) {
      if (!done[std::size_t(i)] && (u < 0 || dist[std::size_t(i)] < dist[std::size_t(u)])) u = i;
    }
    if (u < 0 || std::isinf(dist[std::size_t(u)])) break;
    done[std::size_t(u)] = true;
    for (auto [a, b, c] : edges) {
      if (a == u) dist[std::size_t(b)] = std::min(dist[std::size_t(b)], dist[std::size_t(u)] + c);
    }
  }
  return std::isinf(dist[std::size_t(t)]) ? -1.0 : dist[std::size_t(t)];
}

TEST(WaypointGraph, EqualsDijkstraOnRandomGraphsWithCheapEdges) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Pcg32 rng(seed, 21);
    WaypointGraph g;
    const int n = 60;
    std::vector<Vec2> pos;
    for (int i = 0; i < n; ++i) {
      pos.push_back(Vec2{rng.uniform(0, 100), rng.uniform(0, 100)});
      g.addNode(pos.back());
    }
    std::vector<std::tuple<int, int, double>> edges;
    for (int e = 0; e < 150; ++e) {
      int a = int(rng.next() % n), b = int(rng.next() % n);
      if (a == b) continue;
      double len = std::hypot(pos[std::size_t(a)].x - pos[std::size_t(b)].x,
                              pos[std::size_t(a)].y - pos[std::size_t(b)].y);
      // Some edges are far cheaper than their length (a road), which A* must not overlook.
      double cost = len * rng.uniform(0.2, 2.0) + 0.01;
      g.addEdge(a, b, cost, 0, false);
      edges.emplace_back(a, b, cost);
    }
    WaypointPath path;
    for (int q = 0; q < 20; ++q) {
      int s = int(rng.next() % n), t = int(rng.next() % n);
      double expected = dijkstra(edges, n, s, t);
      ASSERT_EQ(g.findPath(s, t, 0, path), expected >= 0) << "seed " << seed;
      if (expected >= 0) {
        EXPECT_NEAR(path.cost, expected, 1e-9) << "seed " << seed;
      }
    }
  }
}

}  // namespace
}  // namespace zonesim::ai
