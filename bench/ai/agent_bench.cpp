// agent_bench: AI time per tick of zone agents (zone_node/systems/agent_system.h) for N agents
// of each behaviour, on one core, with wandering NPCs around as what they see. Each case builds
// a one-zone scene from text (the agents: keys of docs/scene-format.md), creates the scene's
// entities, and times AgentSystem::step alone (the wanderers are stepped untimed between ticks).
// Prints one row per case: behaviour, agents, us per tick, ns per agent update, paths planned.
// With --decide-every, instead times time-sliced decisions (agents.decide_every) for a few
// behaviours against every agent deciding every tick, on the same wanderers, and prints what
// slicing changes in the outcome; a last row per behaviour ("lod") decides by the scene's lod
// bands around one player at (23, 33) instead (near 15 m, to 40 m every 2 ticks, beyond 8).
//
//   build/bin/agent_bench [--ticks T] [--sizes 1000,10000] [--decide-every 1,2,4,8]
//   build/bin/agent_bench --lod-sweep [--ticks T] [--sizes N]   (CSV over LOD bands)

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "bench/bench_args.h"
#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/agent_system.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/systems/neighbourhood.h"
#include "zone_node/systems/npc_movement.h"
#include "zone_node/world_map.h"
#include "zone_node/zone_map.h"

using namespace zonesim;
using namespace zonesim::zone;

namespace {

struct Case {
  const char* label;
  const char* type;  // the agent type's keys, indented for the scene below
  bool map;
};

const Case kCases[] = {
    {"fsm (guard.yaml)",
     "behaviour: fsm\n      machine: " ZONESIM_SOURCE_DIR "/scenes/ai/guard.yaml\n"
     "      actions: {patrol: wander, chase: chase, attack: attack, flee: flee}",
     false},
    {"guard (C++)", "behaviour: guard", false},
    {"hierarchical fsm",
     "behaviour: fsm\n      machine: " ZONESIM_SOURCE_DIR "/scenes/ai/guard_hierarchical.yaml\n"
     "      actions: {patrol: wander, chase: chase, attack: attack, flee: flee}",
     false},
    {"decision tree",
     "behaviour: tree\n      tree: {if: health < 40, then: flee, else: {if: enemy_distance < 6, "
     "then: chase, else: wander}}",
     false},
    {"fuzzy",
     "behaviour: fuzzy\n      fuzzy:\n        - {input: enemy_distance, membership: [0, 0, 2, 5], "
     "speed: 3, approach: -1}\n        - {input: enemy_distance, membership: [2, 5, 1e12, 1e12], "
     "speed: 1.5, approach: 0.3}",
     false},
    {"goap",
     "behaviour: goap\n      goap:\n        facts: [has_axe, has_wood, stored]\n        goal: "
     "{stored: true}\n        actions:\n          - {name: axe, effects: {has_axe: true}, cost: 2, "
     "at: [20, 20]}\n          - {name: chop, pre: {has_axe: true}, effects: {has_wood: true}, "
     "cost: 1, at: [100, 100], duration_s: 2}\n          - {name: gather, effects: {has_wood: "
     "true}, cost: 5, at: [50, 110]}\n          - {name: store, pre: {has_wood: true}, effects: "
     "{has_wood: false, stored: true}, cost: 1, at: [64, 64], duration_s: 1}",
     false},
    {"travel (straight)", "behaviour: travel\n      goals: [[20, 22], [100, 22]]", false},
    {"travel (A* paths)",
     "behaviour: travel\n      navigate: true\n      goals: [[20, 22], [100, 22]]", true},
};

// Agent LOD for the slicing table: bands around one player in the agents' region (the LOD
// sweep replaces it).
std::string g_lod = "lod: {near_radius: 15, far_radius: 40, mid_every: 2, far_every: 8}\n";
const crowd::Vec2 kLodPlayer{23, 33};

std::string sceneText(const Case& c, int agents, int paths_per_tick, bool hpa, int decide_every = 1,
                      bool lod = false) {
  std::string s =
      "world: {min: [0, 0, 0], max: [128, 10, 128]}\ntick: {dt: 0.05}\nseed: 3\n"
      "zones: {columns: 1, rows: 1}\nhalo: {width: 10}\n"
      "populations:\n  - {kind: npc, count: " +
      std::to_string(std::max(1, agents / 4)) + ", speed: [0.8, 1.6]}\n";
  if (c.map)
    s += "map: {file: " ZONESIM_SOURCE_DIR
         "/scenes/maps/courtyard.map, origin: [0, 0, 0], cell_size: 2}\n";
  s += "agents:\n  types:\n    - name: t\n      " + std::string(c.type) +
       "\n      speed: 3\n      sight: 8\n  populations:\n    - {type: t, count: " +
       std::to_string(agents) + ", region: {min: [6, 6], max: [40, 60]}}\n";
  s += "  paths: {planner: " + std::string(hpa ? "hpa" : "astar") +
       ", cluster_size: 8, paths_per_tick: " + std::to_string(paths_per_tick) + "}\n";
  s += "  decide_every: " + std::to_string(decide_every) + "\n";
  if (lod) s += g_lod;
  return s;
}

void run(const Case& c, int agents, int ticks, int paths_per_tick, bool hpa, const char* label) {
  Scene scene = parseScene(sceneText(c, agents, paths_per_tick, hpa), "bench");
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  AgentSystem system(scene, map.get());
  WanderMovement wander(scene);
  LoneZone lone{scene.dt};  // wanderers do not separate: lone.near is never queried
  double seconds = 0;
  std::uint64_t planned = 0, updates = 0;
  for (int t = 0; t < ticks; ++t) {
    auto t0 = std::chrono::steady_clock::now();
    const TickCounters& s = lone.step(system, store, std::uint64_t(t));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    planned += s.paths_planned;
    updates += s.agents;
    lone.step(wander, store, std::uint64_t(t));
  }
  std::printf("| %s | %d | %.0f | %.0f | %llu |\n", label, agents, seconds / ticks * 1e6,
              seconds / double(updates) * 1e9, (unsigned long long)planned);
}

/// What a sliced run did: its time, and the outcome compared below.
struct SlicedRun {
  double us_per_tick = 0;
  double decisions_per_tick = 0;
  std::uint64_t transitions = 0, arrivals = 0, attack_ticks = 0, chase_ticks = 0;
  std::vector<Vec3> end;  // agents' final positions, in id order
};

SlicedRun runSliced(const Case& c, int agents, int ticks, int every, bool lod = false) {
  Scene scene = parseScene(sceneText(c, agents, 8, false, every, lod), "bench");
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& r) { store.add(r); });
  std::unique_ptr<ZoneMap> map = ZoneMap::load(scene);
  AgentSystem system(scene, map.get());
  WanderMovement wander(scene);
  LoneZone lone{scene.dt};
  if (lod) lone.players = {kLodPlayer};
  SlicedRun out;
  double seconds = 0;
  std::uint64_t decisions = 0;
  for (int t = 0; t < ticks; ++t) {
    auto t0 = std::chrono::steady_clock::now();
    const TickCounters& s = lone.step(system, store, std::uint64_t(t));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    decisions += system.lastStats().decisions;
    out.transitions += s.agent_transitions;
    for (std::size_t i = 0; i < store.size(); ++i) {
      if (store.agent[i].type < 0) continue;
      out.attack_ticks += store.agent[i].action == int(AgentAction::Attack);
      out.chase_ticks += store.agent[i].action == int(AgentAction::Chase);
    }
    lone.step(wander, store, std::uint64_t(t));
  }
  std::vector<std::pair<std::uint64_t, Vec3>> ends;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.agent[i].type < 0) continue;
    out.arrivals += std::uint64_t(store.agent[i].arrivals);
    ends.emplace_back(store.id[i].value, store.pos[i]);
  }
  std::sort(ends.begin(), ends.end(), [](auto& a, auto& b) { return a.first < b.first; });
  for (auto& e : ends) out.end.push_back(e.second);
  out.us_per_tick = seconds / ticks * 1e6;
  out.decisions_per_tick = double(decisions) / ticks;
  return out;
}

/// The slicing table: each behaviour at each decide_every, against decide_every 1.
void slicingTable(const std::vector<int>& sizes, const std::vector<int>& everies, int ticks) {
  std::printf(
      "| behaviour | agents | decide_every | us/tick | speed-up | decisions/tick | "
      "transitions | agent-ticks chasing | attacking | arrivals | end pos error mean m "
      "| max m |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (int n : sizes) {
    for (const Case& c : kCases) {
      const std::string label = c.label;
      if (label != "fsm (guard.yaml)" && label != "decision tree" && label != "fuzzy" &&
          label != "travel (A* paths)")
        continue;
      SlicedRun full;
      for (int variant = 0; variant <= int(everies.size()); ++variant) {
        const bool lod = variant == int(everies.size());  // the last row: LOD bands instead
        const int every = lod ? 1 : everies[std::size_t(variant)];
        SlicedRun r = runSliced(c, n, ticks, every, lod);
        if (variant == 0) full = r;
        double sum = 0, worst = 0;
        for (std::size_t k = 0; k < r.end.size() && k < full.end.size(); ++k) {
          const double e = (r.end[k] - full.end[k]).norm();
          sum += e;
          worst = std::max(worst, e);
        }
        const std::string k = lod ? "lod" : std::to_string(every);
        std::printf(
            "| %s | %d | %s | %.0f | %.2f | %.0f | %llu | %llu | %llu | %llu | %.2f | "
            "%.2f |\n",
            c.label, n, k.c_str(), r.us_per_tick, full.us_per_tick / r.us_per_tick,
            r.decisions_per_tick, (unsigned long long)r.transitions,
            (unsigned long long)r.chase_ticks, (unsigned long long)r.attack_ticks,
            (unsigned long long)r.arrivals, r.end.empty() ? 0.0 : sum / double(r.end.size()),
            worst);
        std::fflush(stdout);
      }
    }
  }
}

/// Work-precision sweep of the agents' LOD bands (issue 19): for the guard machine and the
/// decision tree, each near radius (far radius 2.5x it, middle band every 2 ticks) and far
/// period against every agent deciding every tick: CSV rows for bench/plot_lod_sweep.py, the
/// error being the agents' mean end position difference.
void lodSweep(int agents, int ticks) {
  for (const Case& c : kCases) {
    const std::string label = c.label;
    if (label != "fsm (guard.yaml)" && label != "decision tree") continue;
    const SlicedRun full = runSliced(c, agents, ticks, 1, false);
    for (double near : {8.0, 15.0, 30.0}) {
      for (int k : {2, 4, 8, 16}) {
        g_lod = "lod: {near_radius: " + std::to_string(near) +
                ", far_radius: " + std::to_string(2.5 * near) +
                ", mid_every: 2, far_every: " + std::to_string(k) + "}\n";
        const SlicedRun r = runSliced(c, agents, ticks, 1, true);
        double sum = 0;
        for (std::size_t i = 0; i < r.end.size(); ++i) sum += (r.end[i] - full.end[i]).norm();
        std::printf("agents %s,%d,%g,%g,%d,%.4f,%.3f,%.3f,end_pos_error_m,%.4f\n",
                    label == "decision tree" ? "(tree)" : "(fsm)", agents, near, 2.5 * near, k,
                    r.us_per_tick * 1e-3, full.us_per_tick / r.us_per_tick,
                    full.decisions_per_tick / r.decisions_per_tick,
                    r.end.empty() ? 0.0 : sum / double(r.end.size()));
        std::fflush(stdout);
      }
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  int ticks = 200;
  std::vector<int> sizes{1000, 10000};
  std::vector<int> everies;
  bool sweep = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--lod-sweep")) {
      sweep = true;
      continue;
    }
    if (i + 1 >= argc) break;
    if (!std::strcmp(argv[i], "--ticks")) ticks = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--sizes")) sizes = bench::parseCounts("--sizes", argv[i + 1]);
    if (!std::strcmp(argv[i], "--decide-every"))
      everies = bench::parseCounts("--decide-every", argv[i + 1]);
    ++i;
  }
  if (sweep) {
    lodSweep(sizes.front(), ticks);
    return 0;
  }
  if (!everies.empty()) {
    slicingTable(sizes, everies, ticks);
    return 0;
  }
  std::printf("| behaviour | agents | us/tick | ns/agent update | paths planned |\n");
  std::printf("|---|---|---|---|---|\n");
  for (int n : sizes) {
    for (const Case& c : kCases) {
      if (c.map) {
        run(c, n, ticks, 1000000, false, "travel (A* paths, budget off)");
        run(c, n, ticks, 8, false, "travel (A* paths, 8/tick)");
        run(c, n, ticks, 8, true, "travel (HPA* 8, 8/tick)");
      } else {
        run(c, n, ticks, 8, false, c.label);
      }
    }
  }
}
