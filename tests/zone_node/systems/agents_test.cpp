// AI agents in a zone (zone_node/systems/agent_*.h) configured from scenes: the interpreted and
// hand-coded guard make the same transitions, GOAP agents execute the cheapest plan, decision
// trees and fuzzy machines act on what agents see, and scene mistakes name their line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/agent_system.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/world_map.h"
#include "zone_node/zone_fixture.h"
#include "zone_node/zone_map.h"
#include "zone_node/zone_node.h"

namespace zonesim::zone {
namespace {

std::string source(const std::string& rel) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + rel;
}

int typeIndex(const Scene& s, const std::string& name) {
  for (std::size_t t = 0; t < s.agents.types.size(); ++t)
    if (s.agents.types[t].name == name) return int(t);
  return -1;
}

TEST(Agents, InterpretedAndHandCodedGuardsMakeTheSameTransitions) {
  // The same scene twice: guards run the machine file in one, the C++ GuardMachine in the
  // other. Same seed, same ids, same senses: identical states and positions every tick.
  Scene file = loadScene(source("scenes/agents.yaml"));
  Scene coded = file;
  int guard = typeIndex(file, "guard");
  ASSERT_GE(guard, 0);
  coded.agents.types[std::size_t(guard)].behaviour = AgentType::Behaviour::Guard;
  ZoneNode a(file, MPI_COMM_WORLD, testing::localZone(0));
  ZoneNode b(coded, MPI_COMM_WORLD, testing::localZone(0));
  std::set<int> states_seen;
  int guards = 0;
  for (int tick = 0; tick < 400; ++tick) {
    a.tick();
    b.tick();
    ASSERT_EQ(a.store().size(), b.store().size());
    guards = 0;
    for (std::size_t i = 0; i < a.store().size(); ++i) {
      const AgentData& x = a.store().agent[i];
      if (x.type != guard) continue;
      ++guards;
      const AgentData& y = b.store().agent[i];
      ASSERT_EQ(a.store().id[i], b.store().id[i]);
      ASSERT_EQ(x.state, y.state) << "tick " << tick << " agent " << i;
      ASSERT_EQ(x.transitions, y.transitions);
      ASSERT_EQ(x.action, y.action);
      ASSERT_EQ(a.store().pos[i], b.store().pos[i]);
      states_seen.insert(x.state);
    }
  }
  EXPECT_EQ(guards, 40);
  // Patrol, chase, attack and flee all happened: the comparison covered every transition.
  EXPECT_EQ(states_seen.size(), 4u);
  int transitions = 0;
  for (std::size_t i = 0; i < a.store().size(); ++i)
    if (a.store().agent[i].type == guard) transitions += a.store().agent[i].transitions;
  EXPECT_GT(transitions, 100);
}

TEST(Agents, HierarchicalSentriesKeepCombatTimerAcrossSubstates) {
  Scene s = loadScene(source("scenes/agents.yaml"));
  int sentry = typeIndex(s, "sentry");
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(0));
  std::set<int> actions;
  for (int tick = 0; tick < 400; ++tick) {
    node.tick();
    for (std::size_t i = 0; i < node.store().size(); ++i)
      if (node.store().agent[i].type == sentry) actions.insert(node.store().agent[i].action);
  }
  // Leaf states of the nested combat state act, and so do the top-level ones.
  EXPECT_TRUE(actions.count(int(AgentAction::Chase)));
  EXPECT_TRUE(actions.count(int(AgentAction::Wander)));
  EXPECT_TRUE(actions.count(int(AgentAction::Attack)));
}

const char* kWorkers = R"(
world: {min: [0, 0, 0], max: [100, 10, 100]}
tick: {dt: 0.1}
seed: 5
zones: {columns: 1, rows: 1}
agents:
  types:
    - name: worker
      behaviour: goap
      goap:
        facts: [has_axe, has_wood, wood_stored]
        goal: {wood_stored: true}
        actions:
          - {name: get_axe, effects: {has_axe: true}, cost: AXE, at: [20, 20], duration_s: 1}
          - {name: chop, pre: {has_axe: true}, effects: {has_wood: true}, cost: 1, at: [50, 80], duration_s: 2}
          - {name: gather, effects: {has_wood: true}, cost: 5, at: [80, 30], duration_s: 3}
          - {name: store, pre: {has_wood: true}, effects: {has_wood: false, wood_stored: true}, cost: 1, at: [50, 50], duration_s: 1}
      speed: 4
      sight: 0
  populations:
    - {type: worker, count: 12}
)";

// Runs workers until all are done; returns their executed plans.
std::vector<AgentData> runWorkers(const std::string& axe_cost) {
  std::string text = kWorkers;
  text.replace(text.find("AXE"), 3, axe_cost);
  Scene s = parseScene(text, "workers");
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(0));
  for (int tick = 0; tick < 1500; ++tick) node.tick();
  return {node.store().agent.begin(), node.store().agent.end()};
}

TEST(Agents, GoapWorkersExecuteTheCheapestPlan) {
  // Axe cheap: get_axe (2) + chop (1) + store (1) = 4 beats gather (5) + store (1) = 6.
  for (const AgentData& a : runWorkers("2")) {
    ASSERT_EQ(a.plan_length, 3);
    EXPECT_EQ(a.plan[0], 0);
    EXPECT_EQ(a.plan[1], 1);
    EXPECT_EQ(a.plan[2], 3);
    EXPECT_EQ(a.plan_step, 3);  // executed to the end
    EXPECT_DOUBLE_EQ(a.plan_cost, 4.0);
    EXPECT_EQ(a.facts, 0b101u);  // has_axe, wood_stored; the wood went into the store
  }
  // Axe dear: 6 + 1 + 1 = 8 loses to gather + store = 6.
  for (const AgentData& a : runWorkers("6")) {
    ASSERT_EQ(a.plan_length, 2);
    EXPECT_EQ(a.plan[0], 2);
    EXPECT_EQ(a.plan[1], 3);
    EXPECT_EQ(a.plan_step, 2);
    EXPECT_DOUBLE_EQ(a.plan_cost, 6.0);
    EXPECT_EQ(a.facts, 0b100u);
  }
}

TEST(Agents, TreeAndFuzzyAgentsActOnWhatTheySee) {
  Scene s = loadScene(source("scenes/agents.yaml"));
  int scout = typeIndex(s, "scout"), skittish = typeIndex(s, "skittish");
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(0));
  int chases = 0, flees_near = 0, blended = 0;
  for (int tick = 0; tick < 300; ++tick) {
    node.tick();
    for (std::size_t i = 0; i < node.store().size(); ++i) {
      const AgentData& a = node.store().agent[i];
      if (a.type == scout && a.action == int(AgentAction::Chase)) ++chases;
      if (a.type == skittish && a.approach < -0.99) ++flees_near;
      if (a.type == skittish && a.approach > -0.99 && a.approach < 0) ++blended;
    }
  }
  EXPECT_GT(chases, 0);      // a wanderer came within 6 m of a scout
  EXPECT_GT(flees_near, 0);  // one came within 2 m of a skittish agent: full flight
  EXPECT_GT(blended, 0);     // between 2 and 5 m: flight blended with curiosity
}

const char* kBadTypes = R"(
world: {min: [0, 0, 0], max: [100, 10, 100]}
tick: {dt: 0.1}
seed: 5
zones: {columns: 1, rows: 1}
agents:
  types:
    - name: a
      behaviour: tree
      tree: {if: stamina < 3, then: idle, else: wander}
)";

TEST(Agents, SceneMistakesNameTheirLine) {
  try {
    parseScene(kBadTypes, "bad.yaml");
    FAIL() << "unknown input accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml:10:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unknown input 'stamina'"), std::string::npos);
  }
  std::string dance = kBadTypes;
  dance.replace(dance.find("idle"), 4, "dance");
  EXPECT_THROW(parseScene(dance, "bad.yaml"), SceneError);
  std::string far = kBadTypes;
  far.replace(far.find("behaviour: tree"), 15, "sight: 50\n      behaviour: tree");
  EXPECT_THROW(parseScene(far, "bad.yaml"), SceneError);  // sight wider than the halo
  // A state of the machine file left without an action is found when the zone loads it.
  std::string fsm = std::string(kBadTypes).substr(0, std::string(kBadTypes).find("    - name: a"));
  fsm += "    - name: g\n      behaviour: fsm\n      machine: " + source("scenes/ai/guard.yaml") +
         "\n      actions: {patrol: wander, chase: chase, attack: attack}\n"
         "  populations: [{type: g, count: 1}]\n";
  Scene s = parseScene(fsm, "fsm.yaml");
  try {
    ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(0));
    FAIL() << "unmapped state accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("fsm.yaml:8:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'flee' has no action"), std::string::npos);
  }
}

}  // namespace
}  // namespace zonesim::zone

namespace zonesim::zone {
namespace {

struct CourierRun {
  int min_arrivals = 1 << 30;
  int replans = 0;
  std::uint64_t max_planned = 0, max_queued = 0, planned = 0;
  int door_crossings_after_close = 0;
  int ticks_on_blocked_cells = 0;
  std::vector<double> end_state;  // id, position and path progress of every agent at the end
};

// Runs scenes/agents_paths.yaml (courtyard map, north door closing at 4 s) with a budget, or
// another courier scene.
CourierRun runCouriers(int paths_per_tick, int expansions_per_tick, int ticks, int cache = 0,
                       const char* scene = "scenes/agents_paths.yaml", int landmarks = 0,
                       bool jps = false) {
  Scene s = loadScene(source(scene));
  const bool mesh = s.agents.paths.planner == AgentPlanner::NavMesh;
  s.agents.paths.paths_per_tick = paths_per_tick;
  s.agents.paths.expansions_per_tick = expansions_per_tick;
  s.agents.paths.cache = cache;
  s.agents.paths.landmarks = landmarks;
  if (jps) s.agents.paths.planner = AgentPlanner::Jps;
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(0));
  const WorldMap& map = *node.worldMap();
  CourierRun r;
  std::set<std::uint64_t> in_door;  // agents standing in the north doorway
  for (int tick = 0; tick < ticks; ++tick) {
    node.tick();
    const TickCounters& c = node.counters();
    r.max_planned = std::max(r.max_planned, c.paths_planned);
    r.max_queued = std::max(r.max_queued, c.paths_queued);
    r.planned += c.paths_planned;
    double time = double(tick + 1) * s.dt;
    std::set<std::uint64_t> in_door_now;
    for (std::size_t i = 0; i < node.store().size(); ++i) {
      ai::Cell cell = map.frame.cellOf({node.store().pos[i].x(), node.store().pos[i].z()});
      // Navmesh paths (agent radius 0) run along wall edges: there only strictly inside a
      // cell counts as in it.
      const double fx =
          (node.store().pos[i].x() - map.frame.origin.x) / map.frame.cell_size - cell.x;
      const double fz =
          (node.store().pos[i].z() - map.frame.origin.y) / map.frame.cell_size - cell.y;
      const bool inside = !mesh || (fx > 1e-9 && fz > 1e-9);
      bool door = cell.x == 22 && cell.y >= 10 && cell.y <= 12 && inside;
      if (door) in_door_now.insert(node.store().id[i].value);
      // Entering the doorway once it is shut (one caught in it when it shut may walk out).
      if (door && time > 4.0 + s.dt && !in_door.count(node.store().id[i].value))
        ++r.door_crossings_after_close;
      if (!door && inside && !map.grid.passable(cell.x, cell.y)) ++r.ticks_on_blocked_cells;
    }
    in_door = std::move(in_door_now);
  }
  for (std::size_t i = 0; i < node.store().size(); ++i) {
    r.min_arrivals = std::min(r.min_arrivals, int(node.store().agent[i].arrivals));
    r.replans += node.store().agent[i].replans;
    const AgentData& a = node.store().agent[i];
    r.end_state.insert(r.end_state.end(),
                       {double(node.store().id[i].value), node.store().pos[i].x(),
                        node.store().pos[i].z(), a.travelled, double(a.nav), double(a.arrivals)});
  }
  return r;
}

TEST(Agents, CouriersReachTheirGoalsAndReplanAroundAClosedDoor) {
  CourierRun r = runCouriers(1000, 0, 1400);
  EXPECT_GE(r.min_arrivals, 2);  // every courier reached a goal in the yard and one in the hall
  EXPECT_GT(r.replans, 5);       // the door cut paths, which were planned again
  EXPECT_EQ(r.door_crossings_after_close, 0);
  EXPECT_EQ(r.ticks_on_blocked_cells, 0);  // splines through the cells never enter a wall
}

TEST(Agents, CouriersPlanningWithLandmarksReachTheirGoalsAndReplanAroundAClosedDoor) {
  // agents.paths.landmarks: A* with 8 landmarks, rebuilt after the door closes.
  CourierRun r = runCouriers(1000, 0, 1400, 0, "scenes/agents_paths.yaml", 8);
  EXPECT_GE(r.min_arrivals, 2);
  EXPECT_GT(r.replans, 5);
  EXPECT_EQ(r.door_crossings_after_close, 0);
  EXPECT_EQ(r.ticks_on_blocked_cells, 0);
}

TEST(Agents, CouriersPlanningWithJumpPointSearchReachTheirGoalsAndReplanAroundAClosedDoor) {
  // map.navigation: jps, with and without landmarks: the same optimal lengths as A*.
  for (int landmarks : {0, 8}) {
    CourierRun r = runCouriers(1000, 0, 1400, 0, "scenes/agents_paths.yaml", landmarks, true);
    EXPECT_GE(r.min_arrivals, 2) << landmarks << " landmarks";
    EXPECT_GT(r.replans, 5) << landmarks << " landmarks";
    EXPECT_EQ(r.door_crossings_after_close, 0) << landmarks << " landmarks";
    EXPECT_EQ(r.ticks_on_blocked_cells, 0) << landmarks << " landmarks";
  }
}

TEST(Agents, NavMeshCouriersReachTheirGoalsAndReplanAroundAClosedDoor) {
  // scenes/agents_navmesh.yaml: the same couriers walking navigation-mesh paths.
  CourierRun r = runCouriers(1000, 0, 1400, 0, "scenes/agents_navmesh.yaml");
  EXPECT_GE(r.min_arrivals, 2);
  EXPECT_GT(r.replans, 5);
  EXPECT_EQ(r.door_crossings_after_close, 0);
  EXPECT_EQ(r.ticks_on_blocked_cells, 0);  // straight segments between corners stay off walls
}

// The navmesh couriers of scenes/agents_navmesh.yaml with map.agent_radius and/or a static
// 8 x 16 m block in the yard (x 70-78, z 14-30) across their straight way from the hall's door
// to the yard's goal, named by map.static_bodies or not. Per run: the least clearance from a
// wall cell (or the block, where the mesh closes it) of any courier once it walked, how often a
// courier stood inside the block, and the fewest goals reached by a courier that found paths.
struct ShapedMeshRun {
  double closest = 1e9;
  int inside_block = 0, no_path = 0, min_arrivals = 1 << 30;
  int moving = 0, within_radius = 0;  // courier-ticks moving, and of those nearer than the radius
};
ShapedMeshRun runShapedMesh(double radius, bool block, bool block_named, bool doors) {
  Scene s = loadScene(source("scenes/agents_navmesh.yaml"));
  s.map.agent_radius = radius;
  s.map.static_bodies = block_named;
  if (block) {
    SceneBody b;
    b.name = "block";
    b.shape = SceneBody::Shape::Box;
    b.motion = SceneBody::Motion::Static;
    b.position = {74, 2, 22};
    b.size = {8, 4, 16};
    s.physics.bodies.push_back(b);
  }
  if (!doors) s.map.doors.clear();
  ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(0));
  const WorldMap& map = *node.worldMap();
  const double cs = map.frame.cell_size;
  const auto toBox = [](double x, double z, double x0, double z0, double x1, double z1) {
    return std::hypot(std::max({x0 - x, 0.0, x - x1}), std::max({z0 - z, 0.0, z - z1}));
  };
  // Distance from (x, z) to the nearest wall cell's square (and the block where it is closed).
  const auto clearance = [&](double x, double z) {
    double nearest = block && block_named ? toBox(x, z, 70, 14, 78, 30) : 1e9;
    const ai::Cell at = map.frame.cellOf({x, z});
    for (int cy = at.y - 2; cy <= at.y + 2; ++cy)
      for (int cx = at.x - 2; cx <= at.x + 2; ++cx)
        if (!map.grid.passable(cx, cy)) {
          const double x0 = map.frame.origin.x + cx * cs, z0 = map.frame.origin.y + cy * cs;
          nearest = std::min(nearest, toBox(x, z, x0, z0, x0 + cs, z0 + cs));
        }
    return nearest;
  };
  ShapedMeshRun r;
  for (int tick = 0; tick < 1400; ++tick) {
    node.tick();
    for (std::size_t i = 0; i < node.store().size(); ++i) {
      const double x = node.store().pos[i].x(), z = node.store().pos[i].z();
      r.inside_block += x > 70 && x < 78 && z > 14 && z < 30;
      const AgentData& a = node.store().agent[i];
      if (a.nav != std::int32_t(AgentNav::Moving)) continue;
      const double c = clearance(x, z);
      r.closest = std::min(r.closest, c);
      ++r.moving;
      r.within_radius += c < radius;
    }
  }
  for (std::size_t i = 0; i < node.store().size(); ++i) {
    const AgentData& a = node.store().agent[i];
    if (a.nav == std::int32_t(AgentNav::NoPath)) {
      ++r.no_path;
      continue;
    }
    r.min_arrivals = std::min(r.min_arrivals, int(a.arrivals));
  }
  std::printf(
      "radius %.1f m, block %s: closest to a wall %.4f m (%d of %d moving courier-ticks nearer "
      "than the radius), %d courier-ticks inside the block, %d couriers without a path, fewest "
      "goals of the others %d\n",
      radius, block ? (block_named ? "on the mesh" : "not on the mesh") : "none", r.closest,
      r.within_radius, r.moving, r.inside_block, r.no_path, r.min_arrivals);
  return r;
}

TEST(Agents, NavMeshCouriersKeepTheAgentRadiusFromWalls) {
  // The north door stays open: eroded by the radius (a cell is kept only if its whole square
  // has the clearance), the courtyard's other ways from the hall to the yard close. Moving
  // couriers keep the radius but on their way out of the band it takes off: a goal on the
  // mesh's edge leaves a courier standing within it, and it starts from the nearest cell the
  // mesh covers (AgentNavigation::meshStart). Without the radius every courier runs along
  // walls (closest 0).
  ShapedMeshRun r = runShapedMesh(0.8, false, false, false);
  EXPECT_GT(r.closest, 0.0);
  EXPECT_LT(r.within_radius * 20, r.moving);  // under 5 % of the moving ticks
  EXPECT_EQ(r.no_path, 0);
  EXPECT_GE(r.min_arrivals, 2);
  // With the block on the mesh as well.
  ShapedMeshRun both = runShapedMesh(0.8, true, true, false);
  EXPECT_GT(both.closest, 0.0);
  EXPECT_EQ(both.inside_block, 0);
  EXPECT_EQ(both.no_path, 0);
  EXPECT_GE(both.min_arrivals, 2);
}

TEST(Agents, NavMeshCouriersGoRoundTheSceneStaticBodies) {
  ShapedMeshRun ignored = runShapedMesh(0, true, false, true);
  EXPECT_GT(ignored.inside_block, 0);  // the block lies across their way
  ShapedMeshRun r = runShapedMesh(0, true, true, true);
  EXPECT_EQ(r.inside_block, 0);
  EXPECT_EQ(r.no_path, 0);
  EXPECT_GE(r.min_arrivals, 2);
}

TEST(Agents, ABindingPathBudgetIsNeverExceededAndServesEveryone) {
  // Two plans a tick for 60 couriers that all ask at once: the queue carries the rest.
  CourierRun r = runCouriers(2, 0, 900);
  EXPECT_LE(r.max_planned, 2u);
  EXPECT_GT(r.max_queued, 30u);  // the budget did bind
  EXPECT_GE(r.min_arrivals, 1);  // yet every request was served and walked
  // An expansion budget stops a tick's planning once spent (one plan always runs).
  CourierRun e = runCouriers(1000, 300, 900);
  EXPECT_GT(e.max_queued, 0u);
  EXPECT_GE(e.min_arrivals, 1);
}

// agents.paths.audit on the courtyard's couriers (HPA* with 8 landmarks, no cache): every plan
// is compared with the A* optimum, the largest overhead is kept, and no path changes.
TEST(Agents, ThePathAuditMeasuresEveryPlanAndChangesNoOutcome) {
  struct Audited {
    std::vector<double> end;
    std::uint64_t planned = 0, audited = 0, overhead_ppm = 0, max_ppm = 0;
  };
  const auto run = [](const char* scene, bool audit) {
    Scene s = loadScene(source(scene));
    s.agents.paths.cache = 0;
    s.agents.paths.audit = audit;
    ZoneNode node(s, MPI_COMM_WORLD, testing::localZone(0));
    Audited a;
    for (int tick = 0; tick < 300; ++tick) {  // 15 s: the door closes at 4 s, couriers replan
      node.tick();
      const TickCounters& c = node.counters();
      a.planned += c.paths_planned;
      a.audited += c.paths_audited;
      a.overhead_ppm += c.path_overhead_ppm;
      EXPECT_GE(c.path_overhead_max_ppm, a.max_ppm) << "the largest so far never falls";
      a.max_ppm = c.path_overhead_max_ppm;
    }
    for (std::size_t i = 0; i < node.store().size(); ++i)
      a.end.insert(a.end.end(), {node.store().pos[i].x(), node.store().pos[i].z()});
    return a;
  };
  const Audited on = run("scenes/agents_hpa.yaml", true),
                off = run("scenes/agents_hpa.yaml", false);
  std::printf("HPA*: %llu plans audited of %llu, mean overhead %.4f %%, largest %.4f %%\n",
              (unsigned long long)on.audited, (unsigned long long)on.planned,
              on.audited ? 1e-4 * double(on.overhead_ppm) / double(on.audited) : 0.0,
              1e-4 * double(on.max_ppm));
  EXPECT_GT(on.planned, 60u);
  EXPECT_EQ(on.audited, on.planned);  // no cache, and every courier's goal is reachable
  EXPECT_LE(on.overhead_ppm, on.audited * on.max_ppm);
  EXPECT_EQ(on.end, off.end);
  EXPECT_EQ(off.audited, 0u);
  const Audited astar = run("scenes/agents_paths.yaml", true);
  EXPECT_EQ(astar.audited, astar.planned);
  EXPECT_EQ(astar.max_ppm, 0u) << "A* is the optimum";
}

TEST(Agents, ThePathCacheChangesNoOutcomeUnderABindingBudget) {
  // A hit is charged the expansions of the plan it stands for and the cache empties when the
  // door closes, so with or without it the same requests are served in the same ticks.
  CourierRun off = runCouriers(2, 300, 700, 0);
  CourierRun on = runCouriers(2, 300, 700, 1024);
  EXPECT_GT(on.max_queued, 0u);
  EXPECT_EQ(on.end_state, off.end_state);
}

}  // namespace
}  // namespace zonesim::zone

namespace zonesim::zone {
namespace {

// One agent of a decision-tree type and one still wanderer (its enemy) on the courtyard map
// (1 m cells), placed by hand; AgentSystem alone is stepped, so the enemy stays put.
struct Pursuit {
  double final_distance = 0;  // agent to enemy at the end
  double min_distance = 1e9;
  int ticks_on_blocked_cells = 0;
  int steps_into_walls = 0;  // ticks the agent tried to move yet barely did
};

Pursuit runPursuit(const std::string& tree, double sight, double ax, double az, double ex,
                   double ez, int ticks) {
  std::string text =
      "world: {min: [0, 0, 0], max: [64, 10, 64]}\ntick: {dt: 0.05}\nseed: 5\n"
      "zones: {columns: 1, rows: 1}\nhalo: {width: 20}\n"
      "populations:\n  - {kind: npc, count: 1, speed: [1, 1]}\n"
      "map: {file: " +
      source("scenes/maps/courtyard.map") +
      ", origin: [0, 0, 0], cell_size: 1}\n"
      "agents:\n  types:\n    - name: a\n      behaviour: tree\n      tree: " +
      tree + "\n      speed: 3\n      sight: " + std::to_string(sight) +
      "\n  populations:\n    - {type: a, count: 1, region: {min: [2, 2], max: [4, 4]}}\n";
  Scene scene = parseScene(text, "pursuit");
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  AgentSystem system(scene, map.get());
  std::size_t agent = 0, enemy = 0;
  for (std::size_t i = 0; i < store.size(); ++i) (store.agent[i].type >= 0 ? agent : enemy) = i;
  store.pos[agent] = Vec3(ax, store.pos[agent].y(), az);
  store.pos[enemy] = Vec3(ex, store.pos[enemy].y(), ez);
  store.vel[agent] = store.vel[enemy] = Vec3::Zero();
  Pursuit r;
  LoneZone lone{scene.dt};
  for (int t = 0; t < ticks; ++t) {
    Vec3 before = store.pos[agent];
    lone.step(system, store, std::uint64_t(t));
    const AgentData& a = store.agent[agent];
    bool active = a.action == int(AgentAction::Chase) || a.action == int(AgentAction::Flee);
    double moved = std::hypot(store.pos[agent].x() - before.x(), store.pos[agent].z() - before.z());
    if (active && a.nav == std::int32_t(AgentNav::Moving) && moved < 0.5 * 3 * scene.dt)
      ++r.steps_into_walls;
    ai::Cell c = map->world().frame.cellOf({store.pos[agent].x(), store.pos[agent].z()});
    if (!map->world().grid.passable(c.x, c.y)) ++r.ticks_on_blocked_cells;
    double d = std::hypot(store.pos[agent].x() - ex, store.pos[agent].z() - ez);
    r.min_distance = std::min(r.min_distance, d);
    r.final_distance = d;
  }
  return r;
}

TEST(Agents, AChaserOnAMapGoesRoundTheWallToItsQuarry) {
  // Hunter in the west hall, quarry 14 m east behind the hall's wall (column 22, rows 1-9):
  // steering straight would press into the wall; the path leads through the door (rows 10-12).
  Pursuit r = runPursuit("{if: enemy_distance < 1.5, then: attack, else: chase}", 20, 15.5, 4.5,
                         29.5, 4.5, 300);
  std::printf("chaser: closest %.2f m, at the end %.2f m\n", r.min_distance, r.final_distance);
  EXPECT_LT(r.min_distance, 1.5);  // reached it and attacked
  EXPECT_EQ(r.ticks_on_blocked_cells, 0);
  EXPECT_EQ(r.steps_into_walls, 0);
}

TEST(Agents, AFleerOnAMapRunsToOpenGroundNotIntoTheCorner) {
  // Fleer near the hall's north-west corner, threat between it and the hall: straight away from
  // the threat is the corner (at most 7.8 m from it); the refuge is open ground out of sight.
  Pursuit r =
      runPursuit("{if: enemy_distance < 12, then: flee, else: idle}", 12, 3.5, 3.5, 6.5, 6.5, 300);
  std::printf("fleer: at the end %.2f m from the threat\n", r.final_distance);
  EXPECT_GT(r.final_distance, 11.0);
  EXPECT_EQ(r.ticks_on_blocked_cells, 0);
  EXPECT_EQ(r.steps_into_walls, 0);
}

TEST(Agents, TimeSlicedAgentsDecideOnceInEveryWindowOfTicksAndActOnlyThen) {
  // scenes/agents_sliced.yaml (agents.decide_every 4): in any 4 consecutive ticks every agent
  // senses and decides exactly once, and an agent's action or machine state only ever changes
  // on its own decision ticks (all congruent modulo 4).
  Scene scene = loadScene(source("scenes/agents_sliced.yaml"));
  constexpr int kEvery = 4;
  ASSERT_EQ(scene.agents.decide_every, kEvery);
  ZoneNode zone(scene, MPI_COMM_WORLD, testing::localZone(0));
  std::map<std::uint64_t, std::pair<int, int>> last;  // id -> (action, state)
  std::map<std::uint64_t, std::set<int>> change_phase;
  std::vector<std::uint64_t> decisions;
  std::uint64_t agents = 0, changes = 0;
  for (int tick = 0; tick < 400; ++tick) {
    zone.tick();
    const EntityStore& store = zone.store();
    decisions.push_back(zone.counters().agent_decisions);
    agents = zone.counters().agents;
    for (std::size_t i = 0; i < store.size(); ++i) {
      const AgentData& a = store.agent[i];
      if (a.type < 0) continue;
      auto now = std::make_pair(a.action, a.state);
      auto [it, first] = last.try_emplace(store.id[i].value, now);
      if (!first && it->second != now) {
        change_phase[store.id[i].value].insert(tick % kEvery);
        ++changes;
      }
      it->second = now;
    }
  }
  EXPECT_EQ(agents, 140u);
  for (std::size_t t = 0; t + kEvery <= decisions.size(); ++t) {
    std::uint64_t window = 0;
    for (int k = 0; k < kEvery; ++k) window += decisions[t + std::size_t(k)];
    ASSERT_EQ(window, agents) << "ticks " << t << " to " << t + kEvery - 1;
  }
  for (const auto& [id, phases] : change_phase) EXPECT_EQ(phases.size(), 1u) << "agent " << id;
  EXPECT_GT(changes, 100u);  // the property was tested on many decisions
}

TEST(Agents, LevelOfDetailSpacesDecisionsByDistanceToThePlayers) {
  // Agents that stand still (a tree that always idles) around one player: within near_radius
  // they decide every tick, to far_radius every mid_every ticks, beyond every far_every; with
  // decide_every 4 no band decides more often than every 4 ticks. Over any 8 consecutive ticks
  // that is exactly 8, 4 and 1 decisions per agent (2, 2 and 1 with decide_every 4).
  for (int every : {1, 4}) {
    const Scene scene = parseScene(
        "world: {min: [0, 0, 0], max: [200, 10, 200]}\ntick: {dt: 0.05}\nseed: 3\n"
        "zones: {columns: 1, rows: 1}\nhalo: {width: 10}\n"
        "lod: {near_radius: 20, far_radius: 60, mid_every: 2, far_every: 8}\n"
        "agents:\n  decide_every: " +
            std::to_string(every) +
            "\n  types:\n    - {name: post, behaviour: tree, tree: idle, sight: 5}\n"
            "  populations:\n    - {type: post, count: 300}\n",
        "lod.yaml");
    EntityStore store;
    forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
    AgentSystem system(scene, nullptr);
    LoneZone lone{scene.dt};
    lone.players = {crowd::Vec2{100, 100}};
    std::uint64_t bands[3] = {0, 0, 0};
    for (std::size_t i = 0; i < store.size(); ++i) {
      const double d = std::hypot(store.pos[i].x() - 100, store.pos[i].z() - 100);
      ++bands[d <= 20 ? 0 : d <= 60 ? 1 : 2];
    }
    ASSERT_GT(bands[0] * bands[1] * bands[2], 0u) << "every band holds agents";
    std::vector<std::uint64_t> decisions;
    for (std::uint64_t t = 0; t < 24; ++t)
      decisions.push_back(lone.step(system, store, t).agent_decisions);
    const std::uint64_t expected = every == 1 ? 8 * bands[0] + 4 * bands[1] + bands[2]
                                              : 2 * bands[0] + 2 * bands[1] + bands[2];
    for (std::size_t t = 0; t + 8 <= decisions.size(); ++t) {
      std::uint64_t window = 0;
      for (std::size_t k = 0; k < 8; ++k) window += decisions[t + k];
      ASSERT_EQ(window, expected) << "decide_every " << every << ", ticks from " << t;
    }
  }
}

}  // namespace
}  // namespace zonesim::zone
