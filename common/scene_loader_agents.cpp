// The scene's `agents` key (docs/scene-format.md): agent types, their populations and the path
// service's budget. Machine files named here are read by the zone (ai/
// parses them with their own file:line errors); everything in the scene itself is checked here.

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>

#include "common/scene.h"
#include "common/scene_loader_node.h"

namespace zonesim {
namespace {

template <std::size_t N>
int indexOf(const char* const (&names)[N], const std::string& name) {
  for (std::size_t i = 0; i < N; ++i)
    if (name == names[i]) return int(i);
  return -1;
}

template <std::size_t N>
std::string joined(const char* const (&names)[N]) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) out += (i ? ", " : "") + std::string(names[i]);
  return out;
}

int actionOf(const SceneNode& node) {
  int a = indexOf(kAgentActionNames, node.text());
  if (a < 0)
    node.fail("unknown action '" + node.text() + "' (allowed: " + joined(kAgentActionNames) + ")");
  return a;
}

int senseOf(const SceneNode& node, const std::string& name) {
  int s = indexOf(kAgentSenseNames, name);
  if (s < 0) node.fail("unknown input '" + name + "' (allowed: " + joined(kAgentSenseNames) + ")");
  return s;
}

// A tree node: an action name (leaf) or {if: "sense < number", then: node, else: node}.
int readTreeNode(const SceneNode& node, std::vector<AgentTreeNode>& tree, int depth) {
  if (depth > 32) node.fail("tree is deeper than 32 tests");
  int index = int(tree.size());
  tree.emplace_back();
  if (node.isScalar()) {
    tree[std::size_t(index)].action = actionOf(node);
    return index;
  }
  SceneMap m = node.map({"if", "then", "else"});
  SceneNode test = m.required("if");
  std::string text = test.text();
  std::size_t lt = text.find('<');
  if (lt == std::string::npos || text.find_first_of("<>=!", lt + 1) != std::string::npos)
    test.fail("must read 'input < number'");
  auto trim = [](std::string s) {
    s.erase(0, s.find_first_not_of(" \t"));
    s.erase(s.find_last_not_of(" \t") + 1);
    return s;
  };
  std::string sense = trim(text.substr(0, lt)), number = trim(text.substr(lt + 1));
  AgentTreeNode t;
  t.sense = senseOf(test, sense);
  try {
    std::size_t used = 0;
    t.threshold = std::stod(number, &used);
    if (used != number.size()) throw std::invalid_argument(number);
  } catch (const std::exception&) {
    test.fail("'" + number + "' is not a number");
  }
  t.if_less = readTreeNode(m.required("then"), tree, depth + 1);
  t.otherwise = readTreeNode(m.required("else"), tree, depth + 1);
  tree[std::size_t(index)] = t;
  return index;
}

void readFuzzy(const SceneNode& list, AgentType& t) {
  for (const SceneNode& item : list.items()) {
    SceneMap m = item.map({"input", "membership", "speed", "approach"});
    AgentFuzzyState s;
    SceneNode input = m.required("input");
    s.sense = senseOf(input, input.text());
    SceneNode shape = m.required("membership");
    std::vector<SceneNode> corners = shape.items();
    if (corners.size() != 4) shape.fail("must list four corners [a, b, c, d]");
    s.a = corners[0].number();
    s.b = corners[1].number(Limit::atLeast(s.a));
    s.c = corners[2].number(Limit::atLeast(s.b));
    s.d = corners[3].number(Limit::atLeast(s.c));
    m.read("speed", s.speed, Limit::atLeast(0));
    m.read("approach", s.approach, Limit::between(-1, 1));
    t.fuzzy.push_back(s);
  }
  if (t.fuzzy.empty()) list.fail("needs at least one state");
}

void readGoap(const SceneMap& type, const Scene& scene, AgentType& t) {
  SceneMap m = type.section("goap", {"facts", "initial", "goal", "actions"});
  AgentGoap& g = t.goap;
  SceneNode facts = m.required("facts");
  for (const SceneNode& f : facts.items()) {
    std::string name = f.text();
    if (std::find(g.facts.begin(), g.facts.end(), name) != g.facts.end())
      f.fail("fact '" + name + "' is listed twice");
    g.facts.push_back(name);
  }
  if (g.facts.empty() || g.facts.size() > 64) facts.fail("must list 1 to 64 facts");
  auto factBit = [&](const SceneNode& n, const std::string& name) {
    auto it = std::find(g.facts.begin(), g.facts.end(), name);
    if (it == g.facts.end()) n.fail("unknown fact '" + name + "'");
    return std::uint64_t(1) << (it - g.facts.begin());
  };
  // A fact set: a mapping fact -> true/false; every key must be a fact.
  auto factSet = [&](const SceneNode& n, std::uint64_t& mask, std::uint64_t& values) {
    for (const auto& [name, value] : n.entries()) {
      std::uint64_t bit = factBit(value, name);
      mask |= bit;
      bool on = false;
      SceneMap(n).read(name, on);
      if (on) values |= bit;
    }
  };
  if (std::optional<SceneNode> initial = m.optional("initial")) {
    for (const SceneNode& f : initial->items()) g.initial |= factBit(f, f.text());
  }
  factSet(m.required("goal"), g.goal_mask, g.goal_values);
  if (g.goal_mask == 0) m.failAt("goal", "must constrain at least one fact");
  SceneNode actions = m.required("actions");
  for (const SceneNode& item : actions.items()) {
    SceneMap a = item.map({"name", "pre", "effects", "cost", "at", "duration_s"});
    AgentGoapAction act;
    act.name = a.required("name").text();
    if (std::optional<SceneNode> pre = a.optional("pre"))
      factSet(*pre, act.pre_mask, act.pre_values);
    factSet(a.required("effects"), act.effect_mask, act.effect_values);
    if (act.effect_mask == 0) a.failAt("effects", "must set at least one fact");
    a.read("cost", act.cost, Limit::above(0));
    SceneNode at = a.required("at");
    std::tie(act.x, act.z) = groundPointXZ(at, scene.world);
    a.read("duration_s", act.duration_s, Limit::atLeast(0));
    g.actions.push_back(act);
  }
  if (g.actions.empty()) actions.fail("needs at least one action");
}

void readBehaviour(const SceneMap& m, const Scene& scene, AgentType& t) {
  t.behaviour = AgentType::Behaviour(
      m.choice("behaviour", {"fsm", "guard", "tree", "fuzzy", "goap", "travel"}, -1));
  using B = AgentType::Behaviour;
  auto only = [&](const char* key, B b) {
    if (m.optional(key) && t.behaviour != b)
      m.failAt(key, std::string("belongs to another behaviour than '") +
                        m.required("behaviour").text() + "'");
  };
  only("machine", B::Fsm);
  only("actions", B::Fsm);
  only("tree", B::Tree);
  only("fuzzy", B::Fuzzy);
  only("goap", B::Goap);
  switch (t.behaviour) {
    case B::Fsm: {
      SceneNode machine = m.required("machine");
      std::filesystem::path file = machine.text();
      // Relative to the scene file's folder, like the map.
      if (file.is_relative()) file = std::filesystem::path(machine.file()).parent_path() / file;
      t.machine = file.lexically_normal().string();
      SceneNode actions = m.required("actions");
      for (const auto& [state, action] : actions.entries())
        t.state_actions.emplace_back(state, actionOf(action));
      break;
    }
    case B::Tree:
      readTreeNode(m.required("tree"), t.tree, 0);
      break;
    case B::Fuzzy:
      readFuzzy(m.required("fuzzy"), t);
      break;
    case B::Goap:
      readGoap(m, scene, t);
      break;
    case B::Guard:
    case B::Travel:
      break;
  }
}

void readType(const SceneNode& node, Scene& scene) {
  SceneMap m = node.map({"name", "behaviour", "machine", "actions", "tree", "fuzzy", "goap",
                         "speed", "acceleration", "sight", "wander_radius", "arrive_distance",
                         "health", "energy", "goals", "dwell_s", "navigate"});
  AgentType t;
  t.file = node.file();
  t.line = node.line();
  SceneNode name = m.required("name");
  t.name = name.text();
  for (const AgentType& other : scene.agents.types)
    if (other.name == t.name) name.fail("type '" + t.name + "' is defined twice");
  m.required("behaviour");
  readBehaviour(m, scene, t);
  m.read("speed", t.speed, Limit::above(0));
  m.read("acceleration", t.acceleration, Limit::above(0));
  m.read("sight", t.sight, Limit::atLeast(0));
  m.read("wander_radius", t.wander_radius, Limit::above(0));
  m.read("arrive_distance", t.arrive_distance, Limit::above(0));
  SceneMap health = m.section("health", {"damage_range", "damage_per_s", "regen_per_s"});
  health.read("damage_range", t.damage_range, Limit::atLeast(0));
  health.read("damage_per_s", t.damage_per_s, Limit::atLeast(0));
  health.read("regen_per_s", t.regen_per_s, Limit::atLeast(0));
  SceneMap energy = m.section("energy", {"drain_per_s", "recover_per_s"});
  energy.read("drain_per_s", t.energy_drain_per_s, Limit::atLeast(0));
  energy.read("recover_per_s", t.energy_recover_per_s, Limit::atLeast(0));
  if (std::optional<SceneNode> goals = m.optional("goals")) {
    for (const SceneNode& g : goals->items()) t.goals.push_back(groundPointXZ(g, scene.world));
  }
  if (t.behaviour == AgentType::Behaviour::Travel && t.goals.empty())
    m.failAt("goals", "a travelling type needs at least one goal");
  m.read("dwell_s", t.dwell_s, Limit::atLeast(0));
  m.read("navigate", t.navigate);
  if (t.navigate && !scene.map.present())
    m.failAt("navigate", "paths need the scene's map (top-level map: key)");
  // Enemies across a border are seen through the halo; it must reach as far as agents look.
  if (t.sight > scene.halo_width)
    m.failAt("sight", formatNumber(t.sight) + " m is wider than halo.width (" +
                          formatNumber(scene.halo_width) + " m)");
  scene.agents.types.push_back(std::move(t));
}

void readPopulation(const SceneNode& node, Scene& scene) {
  SceneMap m = node.map({"type", "count", "region"});
  AgentPopulation p;
  SceneNode type = m.required("type");
  auto found = std::find_if(scene.agents.types.begin(), scene.agents.types.end(),
                            [&](const AgentType& t) { return t.name == type.text(); });
  if (found == scene.agents.types.end()) type.fail("unknown agent type '" + type.text() + "'");
  p.type = int(found - scene.agents.types.begin());
  p.count = m.required("count").integer(Limit::atLeast(0));
  p.min_x = scene.world.min.x;
  p.min_z = scene.world.min.z;
  p.max_x = scene.world.max.x;
  p.max_z = scene.world.max.z;
  if (std::optional<SceneNode> region = m.optional("region")) {
    SceneMap r = region->map({"min", "max"});
    SceneNode lo = r.required("min"), hi = r.required("max");
    std::tie(p.min_x, p.min_z) = groundPointXZ(lo, scene.world);
    std::tie(p.max_x, p.max_z) = groundPointXZ(hi, scene.world);
    if (p.max_x < p.min_x || p.max_z < p.min_z) hi.fail("must not be below region.min");
  }
  scene.agents.populations.push_back(p);
}

// `map.navigation` names the planner; `agents.paths.planner` is its older spelling, kept so
// existing scenes load unchanged. Both may be given only when they agree.
void readPaths(const SceneMap& agents, const ObstacleMap& map, AgentPathSettings& p) {
  SceneMap m = agents.section("paths", {"planner", "cluster_size", "paths_per_tick",
                                        "expansions_per_tick", "cache", "landmarks", "audit"});
  const int planner = m.choice("planner", {"astar", "hpa", "jps"}, -1);
  const AgentPlanner by_map[] = {AgentPlanner::AStar, AgentPlanner::Hpa, AgentPlanner::NavMesh,
                                 AgentPlanner::Jps};
  const AgentPlanner by_name[] = {AgentPlanner::AStar, AgentPlanner::Hpa, AgentPlanner::Jps};
  if (map.navigation >= 0 && planner >= 0 && by_name[planner] != by_map[map.navigation]) {
    const char* names[] = {"grid", "hpa", "navmesh", "jps"};
    m.failAt("planner", std::string("contradicts map.navigation: ") + names[map.navigation] +
                            " (line " + std::to_string(map.navigation_line) +
                            "); give one of them");
  }
  if (map.navigation >= 0)
    p.planner = by_map[map.navigation];
  else if (planner >= 0)
    p.planner = by_name[planner];
  m.read("cluster_size", p.cluster_size, Limit::between(2, 256));
  m.read("paths_per_tick", p.paths_per_tick, Limit::between(1, 1000000));
  m.read("expansions_per_tick", p.expansions_per_tick, Limit::atLeast(0));
  m.read("cache", p.cache, Limit::atLeast(0));
  m.read("landmarks", p.landmarks, Limit::between(0, 32));
  if (p.landmarks > 0 && p.planner == AgentPlanner::NavMesh)
    m.failAt("landmarks", "serve the grid, hpa and jps planners only (map.navigation)");
  m.read("audit", p.audit);
}

}  // namespace

void readAgents(const SceneMap& root, Scene& scene) {
  std::optional<SceneNode> node = root.optional("agents");
  if (!node) return;
  // Doors are cells of the map (map.doors); the old key is refused rather than ignored, so a
  // scene written for the old layout does not silently lose its doors.
  SceneMap agents = node->map({"types", "populations", "paths", "doors", "decide_every"});
  if (agents.optional("doors"))
    agents.failAt("doors", "moved to map.doors (same keys: at_s, cell, open)");
  for (const SceneNode& t : agents.required("types").items()) readType(t, scene);
  if (std::optional<SceneNode> pops = agents.optional("populations"))
    for (const SceneNode& p : pops->items()) readPopulation(p, scene);
  readPaths(agents, scene.map, scene.agents.paths);
  agents.read("decide_every", scene.agents.decide_every, Limit::between(1, 64));
}

}  // namespace zonesim
