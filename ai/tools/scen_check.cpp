// scen_check MAP SCEN [--planner astar|jps|jps+|hpa] [--direct-distance D] [--landmarks K]: runs
// every problem of a
// MAP (the map path inside the scenario is ignored) and compares each length with the listed
// optimum, at the precision the file lists it with (older files give 2 decimals). Ends with
// `problems N mismatches M us_per_path X mean_overhead A p99_overhead B max_overhead Y` (an
// overhead is a found path's length over the listed optimum, minus 1: a planner's worst case
// shows beside its typical one); exits 1 on a mismatch (for HPA*, which is
// not optimal, a mismatch is a missing or too-short path), 2 on bad input or usage. A* and
// jump point search (jps scans its jumps, jps+ reads them from precomputed tables) must match
// every optimum; jps also checks that each path is a valid
// sequence of moves (its cells are filled in between jump points). --landmarks K gives A*, jump
// point search or HPA* K landmarks (ai/landmark_heuristic.h), built before the clock starts: the
// line then ends `landmarks K landmarks_ms B landmarks_mb M`. --max-overhead F and
// --max-mean-overhead F (grid planners) hold the worst and the mean overhead to those bounds:
// a run over either exits 1, naming the file, the figure and the bound.
//
// --planner navmesh (radius 0, so the mesh covers every passable cell, as the optima assume)
// compares any-angle lengths with the 8-connected optima instead: it ends with
// `problems N mismatches M us_per_path X build_ms B mean_ratio A p99_ratio P min_ratio L
// max_ratio H shorter S mean_saving V max_saving W longer G`, a ratio being the path's length
// over the optimum, a saving 1 - ratio over the shorter paths; a mismatch is a missing path, a
// segment that crosses a blocked cell, or one shorter than the straight line.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ai/grid_map.h"
#include "ai/grid_search.h"
#include "ai/hpa_planner.h"
#include "ai/jump_point_search.h"
#include "ai/landmark_heuristic.h"
#include "ai/navmesh.h"
#include "ai/navmesh_search.h"
#include "ai/parse_error.h"
#include "ai/scenario.h"
#include "ai/segment_cells.h"
#include "common/timer.h"

namespace {

using zonesim::ai::Cell;
using zonesim::ai::GridPath;

int usage() {
  std::fprintf(
      stderr,
      "usage: scen_check MAP SCEN [--planner astar|jps|jps+|hpa|navmesh] "
      "[--direct-distance D] [--landmarks K] [--max-overhead F] [--max-mean-overhead F]\n"
      "  --direct-distance: hpa hands queries whose ends are at most D cells apart to\n"
      "  the optimal jump point search (default %g; negative: never)\n"
      "  --landmarks: astar, jps, jps+ and hpa estimate costs with K landmarks as well (1 to %d)\n"
      "  --max-overhead, --max-mean-overhead: exit 1 when the worst or the mean overhead (a\n"
      "  path's length over the listed optimum, minus 1) is over F (not for navmesh)\n",
      zonesim::ai::HpaConfig{}.direct_distance, zonesim::ai::LandmarkHeuristic::kMaxLandmarks);
  return 2;
}

double rankOf(const std::vector<double>& sorted, double q) {
  return sorted.empty() ? 0.0 : sorted[std::size_t(q * double(sorted.size() - 1) + 0.5)];
}

// The navmesh report (see the top of the file); returns the exit status.
int checkNavMesh(const zonesim::ai::GridMap& map,
                 const std::vector<zonesim::ai::ScenarioProblem>& problems,
                 const std::string& scen_path) {
  using namespace zonesim::ai;
  zonesim::Stopwatch build;
  NavMesh mesh(map, NavMeshConfig{});
  const double build_ms = build.elapsedSeconds() * 1e3;
  NavMeshSearch search(mesh);
  std::vector<NavPath> paths(problems.size());
  std::vector<char> found(problems.size(), 0);
  zonesim::Stopwatch clock;
  for (std::size_t i = 0; i < problems.size(); ++i)
    found[i] = search.findPath(problems[i].start, problems[i].goal, paths[i]) ? 1 : 0;
  const double seconds = clock.elapsedSeconds();
  int mismatches = 0, longer = 0;
  std::vector<double> ratios, savings;
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const ScenarioProblem& p = problems[i];
    const NavPath& path = paths[i];
    int crossings = 0;
    for (std::size_t k = 1; k < path.points.size(); ++k)
      forEachCellCrossed(path.points[k - 1], path.points[k], [&](Cell c) {
        if (!map.passable(c.x, c.y)) ++crossings;
      });
    const double straight = std::hypot(p.goal.x - p.start.x, p.goal.y - p.start.y);
    const bool bad = !found[i] || crossings > 0 || path.length < straight - 1e-9;
    if (bad && ++mismatches <= 10)
      std::fprintf(stderr, "%s:%d: (%d,%d)->(%d,%d) %s\n", scen_path.c_str(), p.line, p.start.x,
                   p.start.y, p.goal.x, p.goal.y,
                   !found[i]       ? "no path"
                   : crossings > 0 ? "crosses a blocked cell"
                                   : "shorter than the straight line");
    if (!found[i] || p.optimal <= 0) continue;
    const double ratio = path.length / p.optimal;
    ratios.push_back(ratio);
    // Beyond the file's rounding of the optimum.
    if (path.length < p.optimal - 0.5 * p.optimal_step) savings.push_back(1.0 - ratio);
    if (path.length > p.optimal + 0.5 * p.optimal_step) ++longer;
  }
  std::sort(ratios.begin(), ratios.end());
  std::sort(savings.begin(), savings.end());
  double mean = 0, mean_saving = 0;
  for (double r : ratios) mean += r;
  for (double s : savings) mean_saving += s;
  mean = ratios.empty() ? 0 : mean / double(ratios.size());
  mean_saving = savings.empty() ? 0 : mean_saving / double(savings.size());
  std::printf(
      "problems %zu mismatches %d us_per_path %.2f build_ms %.2f mean_ratio %.6f p99_ratio %.6f "
      "min_ratio %.6f max_ratio %.6f shorter %zu mean_saving %.6f max_saving %.6f longer %d\n",
      problems.size(), mismatches, problems.empty() ? 0.0 : seconds * 1e6 / double(problems.size()),
      build_ms, mean, rankOf(ratios, 0.99), ratios.empty() ? 0.0 : ratios.front(),
      ratios.empty() ? 0.0 : ratios.back(), savings.size(), mean_saving,
      savings.empty() ? 0.0 : savings.back(), longer);
  return mismatches > 0 ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace zonesim::ai;
  std::string map_path, scenPath, planner = "astar";
  double direct_distance = HpaConfig{}.direct_distance;
  int landmark_count = 0;
  // Bounds on the overheads; negative: none given.
  double max_overhead = -1.0, max_mean_overhead = -1.0;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--planner" && i + 1 < argc) {
      planner = argv[++i];
    } else if (a.rfind("--planner=", 0) == 0) {
      planner = a.substr(10);
    } else if (a == "--direct-distance" && i + 1 < argc) {
      char* end = nullptr;
      direct_distance = std::strtod(argv[++i], &end);
      if (end == argv[i] || *end != '\0') return usage();
    } else if (a == "--landmarks" && i + 1 < argc) {
      char* end = nullptr;
      const long k = std::strtol(argv[++i], &end, 10);
      if (end == argv[i] || *end != '\0' || k < 1 || k > LandmarkHeuristic::kMaxLandmarks) {
        std::fprintf(stderr, "scen_check: --landmarks %s: not a count from 1 to %d\n", argv[i],
                     LandmarkHeuristic::kMaxLandmarks);
        return 2;
      }
      landmark_count = int(k);
    } else if ((a == "--max-overhead" || a == "--max-mean-overhead") && i + 1 < argc) {
      char* end = nullptr;
      const double bound = std::strtod(argv[++i], &end);
      if (end == argv[i] || *end != '\0' || !(bound >= 0.0) || std::isinf(bound)) {
        std::fprintf(stderr, "scen_check: %s %s: not a finite number >= 0\n", a.c_str(), argv[i]);
        return 2;
      }
      (a == "--max-overhead" ? max_overhead : max_mean_overhead) = bound;
    } else if (!a.empty() && a[0] == '-') {
      return usage();
    } else if (map_path.empty()) {
      map_path = a;
    } else if (scenPath.empty()) {
      scenPath = a;
    } else {
      return usage();
    }
  }
  if (map_path.empty() || scenPath.empty() ||
      (planner != "astar" && planner != "jps" && planner != "jps+" && planner != "hpa" &&
       planner != "navmesh")) {
    return usage();
  }
  if (landmark_count > 0 && planner == "navmesh") {
    std::fprintf(stderr,
                 "scen_check: --landmarks is for --planner astar, jps, jps+ or hpa, not %s\n",
                 planner.c_str());
    return 2;
  }
  if (planner == "navmesh" && (max_overhead >= 0.0 || max_mean_overhead >= 0.0)) {
    std::fprintf(stderr,
                 "scen_check: --max-overhead and --max-mean-overhead are for the grid planners, "
                 "not navmesh (its any-angle paths may be shorter than the optima)\n");
    return 2;
  }
  const bool optimal = planner != "hpa";

  try {
    GridMap map = loadMovingAiMap(map_path);
    auto problems = loadScenario(scenPath);
    for (const auto& p : problems) {
      if (p.map_width != map.width() || p.map_height != map.height()) {
        throw ParseError(scenPath, p.line,
                         "problem is for a " + std::to_string(p.map_width) + "x" +
                             std::to_string(p.map_height) + " map, " + map_path + " is " +
                             std::to_string(map.width()) + "x" + std::to_string(map.height()));
      }
      if (!map.passable(p.start.x, p.start.y) || !map.passable(p.goal.x, p.goal.y)) {
        throw ParseError(scenPath, p.line, "start or goal is blocked on " + map_path);
      }
    }

    if (planner == "navmesh") return checkNavMesh(map, problems, scenPath);

    std::function<bool(Cell, Cell, GridPath&)> plan;
    std::unique_ptr<GridSearch> astar;
    std::unique_ptr<JumpPointSearch> jps;
    std::unique_ptr<HpaPlanner> hpa;
    std::unique_ptr<LandmarkHeuristic> landmarks;
    double landmarks_ms = 0;
    if (landmark_count > 0) {
      zonesim::Stopwatch build;
      landmarks = std::make_unique<LandmarkHeuristic>(map, landmark_count);
      landmarks_ms = build.elapsedSeconds() * 1e3;
    }
    if (planner == "astar") {
      astar = std::make_unique<GridSearch>(map);
      astar->useLandmarks(landmarks.get());
      plan = [&](Cell s, Cell g, GridPath& out) { return astar->findPath(s, g, out); };
    } else if (planner == "jps" || planner == "jps+") {
      jps = std::make_unique<JumpPointSearch>(
          map,
          planner == "jps" ? JumpPointSearch::Jumps::Scanned : JumpPointSearch::Jumps::Precomputed,
          landmarks.get());
      plan = [&](Cell s, Cell g, GridPath& out) { return jps->findPath(s, g, out); };
    } else {
      HpaConfig config;
      config.direct_distance = direct_distance;
      hpa = std::make_unique<HpaPlanner>(map, config);
      hpa->useLandmarks(landmarks.get());
      plan = [&](Cell s, Cell g, GridPath& out) { return hpa->findPath(s, g, out); };
    }

    GridPath path;
    int mismatches = 0;
    std::vector<double> overheads;  // of every found path
    overheads.reserve(problems.size());
    zonesim::Stopwatch clock;
    for (const auto& p : problems) {
      bool found = plan(p.start, p.goal, path);
      bool bad = !found;
      double overhead = 0.0;
      if (found) {
        overhead = p.optimal > 0 ? path.length / p.optimal - 1.0 : path.length;
        // A path is never shorter than the optimum, save for the file's rounding of it.
        bad = optimal ? !agreesWithListed(path.length, p)
                      : path.length < p.optimal * (1.0 - 1e-3) - 1e-3 - 0.5 * p.optimal_step;
        bad = bad || !isValidPath(map, path.cells) || !(path.cells.front() == p.start) ||
              !(path.cells.back() == p.goal);
        overheads.push_back(overhead);
      }
      if (bad) {
        if (++mismatches <= 10) {
          std::fprintf(stderr, "%s:%d: (%d,%d)->(%d,%d) expected %.8g, got %s\n", scenPath.c_str(),
                       p.line, p.start.x, p.start.y, p.goal.x, p.goal.y, p.optimal,
                       found ? std::to_string(path.length).c_str() : "no path");
        }
      }
    }
    double seconds = clock.elapsedSeconds();
    double usPerPath = problems.empty() ? 0.0 : seconds * 1e6 / double(problems.size());
    // After the clock: sorting is the report's, not the planner's.
    std::sort(overheads.begin(), overheads.end());
    double mean = 0.0;
    for (double o : overheads) mean += o;
    mean = overheads.empty() ? 0.0 : mean / double(overheads.size());
    auto rank = [&](double q) {
      return overheads.empty() ? 0.0
                               : overheads[std::size_t(q * double(overheads.size() - 1) + 0.5)];
    };
    std::printf(
        "problems %zu mismatches %d us_per_path %.2f mean_overhead %.6f p99_overhead %.6f "
        "max_overhead %.6f",
        problems.size(), mismatches, usPerPath, mean, rank(0.99), rank(1.0));
    if (landmarks)
      std::printf(" landmarks %zu landmarks_ms %.1f landmarks_mb %.1f",
                  landmarks->landmarks().size(), landmarks_ms, double(landmarks->bytes()) / 1e6);
    std::printf("\n");
    // The bounds, after the figures they judge.
    bool over = false;
    const auto holds = [&](const char* figure, double value, const char* flag, double bound) {
      if (bound < 0.0 || value <= bound) return;
      std::fprintf(stderr, "scen_check: %s: %s %.6f is over %s %g\n", scenPath.c_str(), figure,
                   value, flag, bound);
      over = true;
    };
    holds("max_overhead", rank(1.0), "--max-overhead", max_overhead);
    holds("mean_overhead", mean, "--max-mean-overhead", max_mean_overhead);
    return mismatches > 0 || over ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scen_check: %s\n", e.what());
    return 2;
  }
}
