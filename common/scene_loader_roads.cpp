// The `roads` block of an NPC population (docs/scene-format.md): a waypoint graph with
// weighted, flagged, possibly one-way edges and timed closures, which the population travels.

#include <cmath>
#include <string>
#include <vector>

#include "common/scene.h"
#include "common/scene_loader_crowd.h"

namespace zonesim {
namespace {

/// Bits for a list of flag names, adding names not seen before to `names` (at most 32).
std::uint32_t readFlags(const SceneNode& list, std::vector<std::string>& names) {
  std::uint32_t bits = 0;
  for (const SceneNode& item : list.items()) {
    std::string name = item.text();
    std::size_t k = 0;
    while (k < names.size() && names[k] != name) ++k;
    if (k == names.size()) {
      if (names.size() == 32) item.fail("at most 32 different flags");
      names.push_back(name);
    }
    bits |= 1u << k;
  }
  return bits;
}

NpcRoads::Edge readEdge(const SceneNode& node, NpcRoads& roads) {
  NpcRoads::Edge e;
  const int last = int(roads.nodes.size()) - 1;
  std::optional<SceneNode> cost_node;
  if (node.isScalar()) node.fail("an edge is [a, b] or {a, b, cost, flags, one_way}");
  if (!node.isSequence()) {
    SceneMap m = node.map({"a", "b", "cost", "flags", "one_way"});
    e.a = m.required("a").integer(Limit::between(0, last));
    e.b = m.required("b").integer(Limit::between(0, last));
    cost_node = m.optional("cost");
    if (cost_node) e.cost = cost_node->number(Limit::above(0));
    if (auto flags = m.optional("flags")) e.flags = readFlags(*flags, roads.flag_names);
    m.read("one_way", e.one_way);
  } else {
    std::vector<SceneNode> ends = node.items();
    if (ends.size() != 2) node.fail("an edge is [a, b] or {a, b, cost, flags, one_way}");
    e.a = ends[0].integer(Limit::between(0, last));
    e.b = ends[1].integer(Limit::between(0, last));
  }
  if (e.a == e.b) node.fail("an edge needs two different nodes");
  const ScenePoint& a = roads.nodes[std::size_t(e.a)];
  const ScenePoint& b = roads.nodes[std::size_t(e.b)];
  const double length = std::hypot(b.x - a.x, b.z - a.z);
  if (!cost_node) {
    if (length == 0) node.fail("its nodes coincide: give it a cost");
    e.cost = length;
  }
  return e;
}

/// Nodes reachable from node 0 over edges an NPC may use, forwards or (`reverse`) backwards.
std::vector<bool> reachable(const NpcRoads& roads, bool reverse) {
  std::vector<bool> seen(roads.nodes.size(), false);
  std::vector<int> frontier{0};
  seen[0] = true;
  while (!frontier.empty()) {
    int n = frontier.back();
    frontier.pop_back();
    for (const NpcRoads::Edge& e : roads.edges) {
      if ((e.flags & ~roads.may_use) != 0) continue;
      int from = reverse ? e.b : e.a, to = reverse ? e.a : e.b;
      for (int pass = 0; pass < (e.one_way ? 1 : 2); ++pass) {
        if (from == n && !seen[std::size_t(to)]) {
          seen[std::size_t(to)] = true;
          frontier.push_back(to);
        }
        std::swap(from, to);
      }
    }
  }
  return seen;
}

}  // namespace

void readNpcRoads(const SceneMap& population, const Scene& scene, NpcPopulation& p) {
  if (!population.optional("roads")) return;
  for (const char* other : {"separation", "gather", "flock", "flow", "formation", "colony"}) {
    if (population.optional(other))
      population.failAt(other, "a road population travels its graph, not this");
  }
  NpcRoads& r = p.roads;
  r.enabled = true;
  SceneMap m = population.section("roads", {"nodes", "edges", "may_use", "closures"});
  SceneNode nodes = m.required("nodes");
  for (const SceneNode& item : nodes.items()) r.nodes.push_back(readGroundPoint(item, scene));
  if (r.nodes.size() < 2 || r.nodes.size() > 4096) nodes.fail("needs 2 to 4096 nodes");
  SceneNode edges = m.required("edges");
  for (const SceneNode& item : edges.items()) r.edges.push_back(readEdge(item, r));
  if (r.edges.empty()) edges.fail("needs at least one edge");
  if (auto may = m.optional("may_use")) {
    for (const SceneNode& item : may->items()) {
      std::string name = item.text();
      std::size_t k = 0;
      while (k < r.flag_names.size() && r.flag_names[k] != name) ++k;
      if (k == r.flag_names.size()) item.fail("no edge has the flag '" + name + "'");
      r.may_use |= 1u << k;
    }
  }
  if (auto closures = m.optional("closures")) {
    for (const SceneNode& item : closures->items()) {
      SceneMap c = item.map({"edge", "from", "until"});
      NpcRoads::Closure k;
      k.edge = c.required("edge").integer(Limit::between(0, int(r.edges.size()) - 1));
      k.from = c.required("from").number(Limit::atLeast(0));
      k.until = c.required("until").number(Limit::above(k.from));
      r.closures.push_back(k);
    }
  }
  // Every NPC draws its goals from all nodes, so each must reach each (closures aside).
  std::vector<bool> out = reachable(r, false), in = reachable(r, true);
  for (std::size_t n = 0; n < r.nodes.size(); ++n) {
    if (!out[n] || !in[n])
      nodes.fail("node " + std::to_string(n) +
                 (out[n] ? " cannot reach node 0" : " cannot be reached from node 0") +
                 " over the edges these NPCs may use");
  }
}

}  // namespace zonesim
