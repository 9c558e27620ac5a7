// group_lod_bench: level of detail for formations and ant colonies in a zone
// (zone_node/systems/formation_movement.h, ant_movement.h), the same measures as the crowd LOD
// tables: the system's time per tick, the updates it did, and how far the outcome moved from
// the full-detail run of the same scene. The scene is scenes/courtyard_groups_lod.yaml's:
// F formations of 12 on the courtyard route (one population each) and a colony of A ants,
// around an observer at the nest; full detail against the scene's bands (near 8 m, every 2
// ticks to 20 m, every 4 beyond) and against a far band of every 8 ticks.
//
//   build/bin/group_lod_bench [--formations 1,20] [--ants 40,2000] [--seconds S] [--sweep]
//
// --sweep: CSV of time against outcome over a grid of bands (near radius, far period) for the
// first formation and ant counts (bench/plot_lod_sweep.py).

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "ai/grid_path.h"
#include "ai/grid_search.h"
#include "bench/bench_args.h"
#include "common/scene.h"
#include "zone_node/population.h"
#include "zone_node/systems/ant_movement.h"
#include "zone_node/systems/formation_movement.h"
#include "zone_node/systems/lone_zone.h"
#include "zone_node/world_map.h"

using namespace zonesim;
using namespace zonesim::zone;

namespace {

constexpr crowd::Vec2 kObserver{45.5, 44.5};

struct Variant {
  const char* name;
  bool lod;
  int far_every;
  double near_radius = 8;  // the far radius is 2.5x it
};
constexpr Variant kVariants[] = {{"full", false, 4}, {"lod 2/4", true, 4}, {"lod 2/8", true, 8}};

std::string sceneText(int formations, int ants, const Variant& v) {
  std::string s =
      "world: {min: [0, 0, 0], max: [64, 10, 64]}\ntick: {dt: 0.05}\nseed: 37\n"
      "zones: {columns: 1, rows: 1}\nhalo: {width: 2}\n"
      "map: {file: " ZONESIM_SOURCE_DIR
      "/scenes/maps/courtyard.map, cell_size: 1.0}\n"
      "populations:\n";
  for (int f = 0; f < formations; ++f) {
    s += "  - kind: npc\n    count: 12\n    formation:\n      route: [[16.5, 0, 24.5], [17.5, 0, "
         "50.0], [45.5, 0, 50.5], [37.5, 0, 20.5]]\n      columns: 4\n      spacing: 1.5\n"
         "      separation: {radius: 0.6, weight: 10}\n";
  }
  if (ants > 0) {
    s += "  - kind: npc\n    count: " + std::to_string(ants) +
         "\n    colony: {nest: [45.5, 0, 44.5], food: [44.5, 0, 20.5], alpha: 1.0, beta: 4.0, "
         "knows_food: true, evaporation: 0.05, deposit: 1.0, exploitation: 0.5, "
         "initial_pheromone: 0.01, speed: 3.0, max_steps: 300}\n";
  }
  if (v.lod) {
    s += "lod: {near_radius: " + std::to_string(v.near_radius) +
         ", far_radius: " + std::to_string(2.5 * v.near_radius) +
         ", mid_every: 2, far_every: " + std::to_string(v.far_every) + "}\n";
  }
  return s;
}

struct Run {
  double us_per_tick = 0;
  double updates_per_tick = 0;
  // Formations: mean distance of a member to its slot over the run; ants: trips, the mean
  // route of the last quarter, the colony's trail route at the end.
  double mean_slot_error = 0;
  std::uint64_t trips = 0;
  double recent_route = 0, trail_route = 0;
  std::vector<Vec3> end;  // every NPC's end position, in id order (the store keeps scene order)
};

template <class System>
Run run(const Scene& scene, System& system, EntityStore& store, int from, int ticks,
        const FormationMovement* formations) {
  LoneZone lone{scene.dt};
  lone.players = {kObserver};
  Run r;
  double seconds = 0, updates = 0, slot_sum = 0;
  std::uint64_t slot_samples = 0;
  for (int t = from; t < from + ticks; ++t) {
    const auto t0 = std::chrono::steady_clock::now();
    lone.step(system, store, std::uint64_t(t));
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    updates += double(system.updates());
    if (formations) {
      for (std::size_t i = 0; i < store.size(); ++i) {
        const crowd::Vec2 p{store.pos[i].x(), store.pos[i].z()};
        slot_sum += crowd::length(p - formations->slotPosition(store, i));
        ++slot_samples;
      }
    }
  }
  r.us_per_tick = seconds / ticks * 1e6;
  r.updates_per_tick = updates / ticks;
  r.mean_slot_error = slot_samples ? slot_sum / double(slot_samples) : 0.0;
  for (std::size_t i = 0; i < store.size(); ++i) r.end.push_back(store.pos[i]);
  return r;
}

void endError(const Run& full, const Run& r, double& mean, double& worst) {
  mean = worst = 0;
  for (std::size_t i = 0; i < r.end.size(); ++i) {
    const double e = (r.end[i] - full.end[i]).norm();
    mean += e / double(r.end.size());
    worst = std::max(worst, e);
  }
}

Run formationRun(int formations, const Variant& v, int ticks) {
  Scene scene = parseScene(sceneText(formations, 0, v), "bench");
  auto map = loadWorldMap(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& e) { store.add(e); });
  FormationMovement move(scene, map.get());
  return run(scene, move, store, 0, ticks, &move);
}

Run antRun(int ants, const Variant& v, int ticks) {
  Scene scene = parseScene(sceneText(0, ants, v), "bench");
  auto map = loadWorldMap(scene);
  EntityStore store;
  forEachInitialEntity(scene, [&](const EntityRecordData& e) { store.add(e); });
  AntMovement colony(scene, map.get());
  const int first = ticks * 3 / 4;
  Run r = run(scene, colony, store, 0, first, nullptr);
  const ColonyStats before = colony.stats(0);
  const Run rest = run(scene, colony, store, first, ticks - first, nullptr);
  r.us_per_tick = (r.us_per_tick * first + rest.us_per_tick * (ticks - first)) / ticks;
  r.updates_per_tick =
      (r.updates_per_tick * first + rest.updates_per_tick * (ticks - first)) / ticks;
  const ColonyStats& s = colony.stats(0);
  r.trips = s.trips;
  // No trip in the last quarter (a short run): no route to report.
  r.recent_route = s.trips > before.trips
                       ? (s.length_sum - before.length_sum) / double(s.trips - before.trips)
                       : 0.0;
  r.trail_route = ai::pathLength(colony.trailRoute(0));
  return r;
}

/// Work-precision sweep of the LOD bands (issue 19): CSV rows for bench/plot_lod_sweep.py.
void sweep(int formations, int ants, int ticks) {
  const Variant full{"full", false, 4};
  const Run f_full = formationRun(formations, full, ticks);
  const Run a_full = antRun(ants, full, ticks);
  for (double near : {4.0, 8.0, 16.0}) {
    for (int k : {2, 4, 8, 16}) {
      const Variant v{"sweep", true, k, near};
      const Run f = formationRun(formations, v, ticks);
      std::printf("formation,%d,%g,%g,%d,%.4f,%.3f,%.3f,slot_error_m,%.4f\n", 12 * formations, near,
                  2.5 * near, k, f.us_per_tick * 1e-3, f_full.us_per_tick / f.us_per_tick,
                  f_full.updates_per_tick / f.updates_per_tick, f.mean_slot_error);
      const Run a = antRun(ants, v, ticks);
      std::printf("ants,%d,%g,%g,%d,%.4f,%.3f,%.3f,route_change,%.4f\n", ants, near, 2.5 * near, k,
                  a.us_per_tick * 1e-3, a_full.us_per_tick / a.us_per_tick,
                  a_full.updates_per_tick / a.updates_per_tick,
                  std::abs(a.recent_route - a_full.recent_route) / a_full.recent_route);
      std::fflush(stdout);
    }
  }
}

void formationTable(const std::vector<int>& counts, int ticks) {
  std::printf(
      "\n| formations | members | variant | us/tick | speed-up | updates ratio | mean slot "
      "error m | end pos error mean m | max m |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int f : counts) {
    Run full;
    for (const Variant& v : kVariants) {
      Run r = formationRun(f, v, ticks);
      if (!v.lod) full = r;
      double mean = 0, worst = 0;
      endError(full, r, mean, worst);
      std::printf("| %d | %d | %s | %.1f | %.2f | %.2f | %.3f | %.3f | %.3f |\n", f, 12 * f, v.name,
                  r.us_per_tick, full.us_per_tick / r.us_per_tick,
                  full.updates_per_tick / r.updates_per_tick, r.mean_slot_error, mean, worst);
      std::fflush(stdout);
    }
  }
}

void antTable(const std::vector<int>& counts, int ticks) {
  std::printf(
      "\n| ants | variant | us/tick | speed-up | updates ratio | trips | last-quarter mean "
      "route m | trail route m | A* m |\n|---|---|---|---|---|---|---|---|---|\n");
  for (int a : counts) {
    Run full;
    for (const Variant& v : kVariants) {
      Run r = antRun(a, v, ticks);
      if (!v.lod) full = r;
      Scene scene = parseScene(sceneText(0, a, v), "bench");
      auto map = loadWorldMap(scene);
      ai::GridSearch search(map->grid);
      ai::GridPath best;
      search.findPath(map->frame.cellOf({45.5, 44.5}), map->frame.cellOf({44.5, 20.5}), best);
      std::printf("| %d | %s | %.1f | %.2f | %.2f | %llu | %.1f | %.1f | %.1f |\n", a, v.name,
                  r.us_per_tick, full.us_per_tick / r.us_per_tick,
                  full.updates_per_tick / r.updates_per_tick, (unsigned long long)r.trips,
                  r.recent_route, r.trail_route, best.length);
      std::fflush(stdout);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> formations{1, 20}, ants{40, 2000};
  double seconds = 240;
  bool sweeping = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--formations") && i + 1 < argc) {
      formations = bench::parseCounts("--formations", argv[++i]);
    } else if (!std::strcmp(argv[i], "--ants") && i + 1 < argc) {
      ants = bench::parseCounts("--ants", argv[++i]);
    } else if (!std::strcmp(argv[i], "--sweep")) {
      sweeping = true;
    } else if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) {
      seconds = bench::parseCounts("--seconds", argv[++i]).front();
    } else {
      std::fprintf(stderr, "usage: %s [--formations LIST] [--ants LIST] [--seconds S] [--sweep]\n",
                   argv[0]);
      return 2;
    }
  }
  const int ticks = int(seconds / 0.05);
  if (sweeping) {  // the first of each list
    sweep(formations.front(), ants.front(), ticks);
    return 0;
  }
  std::printf("group_lod_bench: %d ticks of 1/20 s, observer at the nest (45.5, 44.5)\n", ticks);
  formationTable(formations, ticks);
  antTable(ants, ticks);
  return 0;
}
