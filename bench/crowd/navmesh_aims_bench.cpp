// What flow crowds on a navigation mesh pay to build their aims (crowd/flow_waypoints.h),
// beside the grid flow field they are built with: on the Moving AI maps in tests/data and the
// courtyard, one goal (the first open cell in row-major order), the best of --repeat builds of
// the field, the mesh (not eroded, as flow crowds build it) and the aims at clearance 0.3 cells.
//
//   build/bin/navmesh_aims_bench [--repeat 3]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "ai/grid_map.h"
#include "ai/navmesh.h"
#include "crowd/flow_field.h"
#include "crowd/flow_waypoints.h"

namespace {

using Clock = std::chrono::steady_clock;

template <typename F>
double bestMs(int repeat, F&& build) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = Clock::now();
    build();
    best = std::min(best, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace zonesim;
  int repeat = 3;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) {
      repeat = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: navmesh_aims_bench [--repeat N]\n");
      return 2;
    }
  }
  if (repeat < 1) {
    std::fprintf(stderr, "navmesh_aims_bench: --repeat must be at least 1\n");
    return 2;
  }
  const std::string root = ZONESIM_SOURCE_DIR;
  const std::vector<std::string> maps = {
      root + "/tests/data/movingai/8room_000.map", root + "/tests/data/movingai/random512-10-0.map",
      root + "/tests/data/movingai/maze512-1-0.map", root + "/scenes/maps/courtyard.map"};
  std::printf("best of %d builds, one goal per map\n\n", repeat);
  std::printf(
      "| map | size | grid field ms | mesh ms | aims ms | aims bytes "
      "|\n|---|---|---|---|---|---|\n");
  for (const std::string& path : maps) {
    const ai::GridMap map = ai::loadMovingAiMap(path);
    ai::Cell goal{-1, -1};
    for (int y = 0; y < map.height() && goal.x < 0; ++y)
      for (int x = 0; x < map.width() && goal.x < 0; ++x)
        if (map.passable(x, y)) goal = ai::Cell{x, y};
    const double field_ms = bestMs(repeat, [&] { crowd::FlowField f(map, goal); });
    const double mesh_ms = bestMs(repeat, [&] { ai::NavMesh m(map, ai::NavMeshConfig{}); });
    const crowd::FlowField field(map, goal);
    const ai::NavMesh mesh(map, ai::NavMeshConfig{});
    std::vector<float> aims;
    const double aims_ms =
        bestMs(repeat, [&] { aims = crowd::navMeshWaypoints(mesh, field, 0.3, &map); });
    std::printf("| %s | %d x %d | %.1f | %.1f | %.1f | %zu |\n",
                path.substr(path.find_last_of('/') + 1).c_str(), map.width(), map.height(),
                field_ms, mesh_ms, aims_ms, aims.size() * sizeof(float));
  }
}
