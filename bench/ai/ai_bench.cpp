// ai_bench [--stride N] [--clusters 8,16,32] [DATA_DIR]: for each shipped Moving AI map, times
// A* over every N-th scenario problem, then HPA* on the same problems for each cluster size,
// and prints one table row per (map, planner): µs per path, mean and max length overhead
// against the listed optimum, speed-up over A*, the abstraction's size and build time, and the
// time to repair it after one cell changes (a door). Rows `hpaNsK` smooth windows of K
// abstract steps. The `navmesh` row (radius 0) times A* over portals plus the funnel on the
// same problems: its overheads are against the 8-connected optimum, so negative where the
// any-angle path is shorter; nodes are polygons, expanded are portals, repair is a full
// rebuild (the mesh has no local repair), and mem_kb is the mesh's bytes against the grid's
// (one byte a cell) on the astar row.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "ai/grid_search.h"
#include "ai/hpa_planner.h"
#include "ai/navmesh.h"
#include "ai/navmesh_search.h"
#include "ai/scenario.h"
#include "common/timer.h"

namespace {

using namespace zonesim::ai;

struct Row {
  double usPerPath = 0;
  double meanOverhead = 0;
  double maxOverhead = 0;
  long expandedPerPath = 0;
};

template <typename Plan>
Row timePlanner(const std::vector<ScenarioProblem>& problems, Plan&& plan) {
  GridPath path;
  Row row;
  long expanded = 0;
  zonesim::Stopwatch clock;
  for (const auto& p : problems) expanded += plan(p.start, p.goal, path);
  row.usPerPath = clock.elapsedSeconds() * 1e6 / double(problems.size());
  // Overheads in a second, untimed pass so that the timing covers planning only.
  for (const auto& p : problems) {
    plan(p.start, p.goal, path);
    double o = p.optimal > 0 ? path.length / p.optimal - 1.0 : 0.0;
    row.meanOverhead += o;
    row.maxOverhead = std::max(row.maxOverhead, o);
  }
  row.meanOverhead /= double(problems.size());
  row.expandedPerPath = expanded / long(problems.size());
  return row;
}

// The navmesh row: build, paths over the same problems, and a rebuild as its repair.
void benchNavMesh(const char* name, const GridMap& map,
                  const std::vector<ScenarioProblem>& problems, double astarUs) {
  zonesim::Stopwatch build;
  NavMesh mesh(map, NavMeshConfig{});
  const double buildMs = build.elapsedSeconds() * 1e3;
  NavMeshSearch search(mesh);
  NavPath path;
  long expanded = 0;
  zonesim::Stopwatch clock;
  for (const auto& p : problems) {
    search.findPath(p.start, p.goal, path);
    expanded += search.lastExpanded();
  }
  const double us = clock.elapsedSeconds() * 1e6 / double(problems.size());
  double mean = 0, worst = -1;
  for (const auto& p : problems) {
    search.findPath(p.start, p.goal, path);
    const double o = p.optimal > 0 ? path.length / p.optimal - 1.0 : 0.0;
    mean += o;
    worst = std::max(worst, o);
  }
  zonesim::Stopwatch rebuild;
  for (int i = 0; i < 5; ++i) NavMesh again(map, NavMeshConfig{});
  const double repairUs = rebuild.elapsedSeconds() * 1e6 / 5.0;
  std::printf("%-16s %-8s %9zu %10.1f %9ld %9.4f %8.4f %7.2f %8zu %9.1f %9.1f %8.1f\n", name,
              "navmesh", problems.size(), us, expanded / long(problems.size()),
              mean / double(problems.size()), worst, astarUs / us, mesh.polygons().size(), buildMs,
              repairUs, double(mesh.memoryBytes()) / 1024);
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = std::string(ZONESIM_SOURCE_DIR) + "/tests/data/movingai";
  int stride = 1;
  std::vector<int> clusterSizes{8, 16, 32};
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--stride" && i + 1 < argc) {
      stride = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--clusters" && i + 1 < argc) {
      clusterSizes.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');)
        clusterSizes.push_back(std::atoi(item.c_str()));
    } else {
      dir = a;
    }
  }

  std::printf("%-16s %-8s %9s %10s %9s %9s %8s %7s %8s %9s %9s %8s\n", "map", "planner", "problems",
              "us_per_path", "expanded", "mean_ovh", "max_ovh", "speedup", "nodes", "build_ms",
              "repair_us", "mem_kb");
  for (const char* name : {"random512-10-0", "8room_000", "maze512-1-0"}) {
    try {
      GridMap map = loadMovingAiMap(dir + "/" + name + ".map");
      auto all = loadScenario(dir + "/" + name + ".map.scen");
      std::vector<ScenarioProblem> problems;
      for (std::size_t i = 0; i < all.size(); i += std::size_t(stride)) problems.push_back(all[i]);

      GridSearch astar(map);
      Row a = timePlanner(problems, [&](Cell s, Cell g, GridPath& out) {
        astar.findPath(s, g, out);
        return astar.lastStats().expanded;
      });
      std::printf("%-16s %-8s %9zu %10.1f %9ld %9.4f %8.4f %7.2f %8s %9s %9s %8.1f\n", name,
                  "astar", problems.size(), a.usPerPath, a.expandedPerPath, a.meanOverhead,
                  a.maxOverhead, 1.0, "-", "-", "-", double(map.width() * map.height()) / 1024);
      benchNavMesh(name, map, problems, a.usPerPath);

      for (int c : clusterSizes) {
        for (int span : {0, 3}) {
          zonesim::Stopwatch build;
          HpaConfig config{c, 6, span};
          config.direct_distance = -1.0;  // the abstraction alone, as the table reports it
          HpaPlanner hpa(map, config);
          double buildMs = build.elapsedSeconds() * 1e3;
          Row h = timePlanner(problems, [&](Cell s, Cell g, GridPath& out) {
            hpa.findPath(s, g, out);
            return hpa.stats().expanded;
          });
          // Repair cost: close and reopen one passable cell on a cluster border, 20 times.
          GridMap& editable = map;
          Cell door{c - 1, 0};
          for (int y = 0; y < map.height() && !map.passable(door.x, door.y); ++y) door.y = y;
          zonesim::Stopwatch repair;
          for (int i = 0; i < 20; ++i) {
            editable.setPassable(door.x, door.y, i % 2 == 1);
            hpa.cellChanged(door);
          }
          double repairUs = repair.elapsedSeconds() * 1e6 / 20.0;
          std::string label =
              "hpa" + std::to_string(c) + (span > 0 ? "s" + std::to_string(span) : "");
          std::printf("%-16s %-8s %9zu %10.1f %9ld %9.4f %8.4f %7.2f %8d %9.1f %9.1f %8s\n", name,
                      label.c_str(), problems.size(), h.usPerPath, h.expandedPerPath,
                      h.meanOverhead, h.maxOverhead, a.usPerPath / h.usPerPath, hpa.stats().nodes,
                      buildMs, repairUs, "-");
        }
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "ai_bench: %s\n", e.what());
      return 2;
    }
  }
  return 0;
}
