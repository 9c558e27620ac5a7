#include "zone_node/systems/road_movement.h"

#include <cmath>
#include <unordered_map>

#include "ai/waypoint_graph.h"
#include "common/rng.h"
#include "common/scene_npcs.h"

namespace zonesim::zone {

struct RoadMovement::Network {
  std::int32_t population = -1;
  const NpcRoads* roads = nullptr;
  ai::WaypointGraph graph;
  std::vector<std::vector<int>> graph_edges;  // scene edge -> its graph edges (one per way)
  std::vector<bool> open;                     // scene edge -> open at `time`
  double time = -1;
  std::unordered_map<std::uint64_t, int> hops;  // (from, goal) -> next node, while `open` holds
  ai::WaypointPath path;

  /// Opens and shuts the edges for `t`; a change forgets the remembered hops.
  void closeFor(double t) {
    if (t == time) return;
    time = t;
    std::vector<bool> now(roads->edges.size(), true);
    for (const NpcRoads::Closure& c : roads->closures)
      if (t >= c.from && t < c.until) now[std::size_t(c.edge)] = false;
    if (now == open) return;
    for (std::size_t e = 0; e < now.size(); ++e)
      for (int g : graph_edges[e]) graph.setEdgeOpen(g, now[e]);
    open = std::move(now);
    hops.clear();
  }
};

RoadMovement::RoadMovement(const std::vector<NpcPopulation>& npcs) {
  for (std::size_t p = 0; p < npcs.size(); ++p) {
    const NpcRoads& roads = npcs[p].roads;
    if (!roads.enabled) continue;
    auto n = std::make_unique<Network>();
    n->population = std::int32_t(p);
    n->roads = &roads;
    for (const ScenePoint& node : roads.nodes) n->graph.addNode({node.x, node.z});
    for (const NpcRoads::Edge& e : roads.edges) {
      const int id = n->graph.addEdge(e.a, e.b, e.cost, e.flags, !e.one_way);
      // addEdge appends a -> b, then b -> a for a two-way edge.
      n->graph_edges.push_back(e.one_way ? std::vector<int>{id} : std::vector<int>{id, id + 1});
    }
    n->open.assign(roads.edges.size(), true);
    networks_.push_back(std::move(n));
  }
}

RoadMovement::~RoadMovement() = default;

RoadMovement::Network* RoadMovement::networkOf(std::int32_t population) {
  for (auto& n : networks_)
    if (n->population == population) return n.get();
  return nullptr;
}

int RoadMovement::nextHop(std::size_t p, int from, int goal, double time) {
  Network* n = networkOf(std::int32_t(p));
  if (!n || from == goal) return goal;
  n->closeFor(time);
  const std::uint64_t key = (std::uint64_t(std::uint32_t(from)) << 32) | std::uint32_t(goal);
  if (auto it = n->hops.find(key); it != n->hops.end()) return it->second;
  int hop = -1;
  if (n->graph.findPath(from, goal, n->roads->may_use, n->path) && n->path.nodes.size() > 1)
    hop = n->path.nodes[1];
  n->hops.emplace(key, hop);
  return hop;
}

void RoadMovement::step(StepContext& ctx) {
  EntityStore& store = ctx.store;
  const double dt = ctx.dt;
  const double time = double(ctx.tick) * dt;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Npc || store.npc[i].population < 0) continue;
    Network* n = networkOf(store.npc[i].population);
    if (!n) continue;
    NpcData& npc = store.npc[i];
    RoadTripData& trip = crowdState<RoadTripData>(npc);
    const std::vector<ScenePoint>& nodes = n->roads->nodes;
    Vec3& pos = store.pos[i];
    Vec3 heading = Vec3::Zero();
    double budget = npc.max_speed * dt;
    // A fast NPC on short edges may pass several nodes in one tick; each one is a decision.
    for (int passed = 0; passed <= int(nodes.size()); ++passed) {
      const ScenePoint& to = nodes[std::size_t(trip.next_node)];
      const double dx = to.x - pos.x(), dz = to.z - pos.z(), dist = std::hypot(dx, dz);
      if (dist > budget) {
        heading = Vec3(dx / dist, 0, dz / dist);
        pos += budget * heading;
        break;
      }
      pos = Vec3(to.x, pos.y(), to.z);
      budget -= dist;
      if (trip.next_node == trip.goal) {
        // At the goal: draw another node from the NPC's own stream.
        Pcg32 rng = Pcg32::fromState(store.rng_state[i], store.id[i].value);
        int goal = int(rng.next() % std::uint32_t(nodes.size() - 1));
        trip.goal = goal >= trip.next_node ? goal + 1 : goal;
        store.rng_state[i] = rng.state();
      }
      const int hop = nextHop(std::size_t(npc.population), trip.next_node, trip.goal, time);
      if (hop < 0) break;  // every way is shut: wait at the node
      trip.next_node = hop;
    }
    store.vel[i] = npc.max_speed * heading;
  }
}

}  // namespace zonesim::zone
