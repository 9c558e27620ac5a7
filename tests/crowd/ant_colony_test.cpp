// Ant colony optimisation on a small map the ants do not know: over the iterations the
// colony's trail converges to a route close to the A* optimum, and evaporation is what lets
// it: without it the trails of the first, long wandering routes never fade.

#include "crowd/ant_colony.h"

#include <gtest/gtest.h>

#include "ai/grid_path.h"
#include "ai/grid_search.h"

namespace zonesim::crowd {
namespace {

// 16x16: a wall down the middle with a gap near the top (short route) and one at the bottom.
ai::GridMap twoGapMap() {
  ai::GridMap map(16, 16);
  for (int y = 0; y < 16; ++y)
    if (y != 3 && y != 14) map.setPassable(8, y, false);
  for (int x = 3; x < 6; ++x) map.setPassable(x, 8, false);
  return map;
}

const ai::Cell kNest{1, 6}, kFood{14, 6};

double optimum(const ai::GridMap& map) {
  ai::GridSearch search(map);
  ai::GridPath p;
  search.findPath(kNest, kFood, p);
  return p.length;
}

struct ColonyResult {
  double trail = 0;     // length of the colony's trail route (0 when it has none)
  double lastMean = 0;  // mean route length of the ants in the last 10 iterations
  double best = 0;
};

ColonyResult runColony(const ai::GridMap& map, AntColonySettings s, int iterations) {
  AntColony colony(map, kNest, kFood, s);
  ColonyResult r;
  double sum = 0;
  int n = 0;
  for (int it = 0; it < iterations; ++it) {
    AntIteration i = colony.iterate();
    if (it >= iterations - 10 && i.found) {
      sum += i.mean_length;
      ++n;
    }
  }
  std::vector<ai::Cell> route;
  if (colony.trailRoute(route)) {
    EXPECT_TRUE(ai::isValidPath(map, route));
    r.trail = ai::pathLength(route);
  }
  r.lastMean = n ? sum / n : 0;
  r.best = colony.best_length();
  return r;
}

AntColonySettings withEvaporation(double rho, std::uint64_t seed) {
  AntColonySettings s;
  s.evaporation = rho;
  s.seed = seed;
  return s;
}

TEST(AntColony, TrailConvergesNearTheAStarOptimum) {
  ai::GridMap map = twoGapMap();
  const double opt = optimum(map);
  double sumTrail = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    ColonyResult r = runColony(map, withEvaporation(0.1, seed), 100);
    std::printf("seed %d: optimum %.2f, trail %.2f, best %.2f, last mean %.2f\n", int(seed), opt,
                r.trail, r.best, r.lastMean);
    ASSERT_GT(r.trail, 0.0);
    EXPECT_GE(r.trail, opt - 1e-9);  // no route beats A*
    EXPECT_LT(r.trail, 1.15 * opt);
    sumTrail += r.trail;
  }
  EXPECT_LT(sumTrail / 6, 1.05 * opt);
}

TEST(AntColony, WithoutEvaporationTheColonyKeepsWandering) {
  // Mean route length the ants walk in the last iterations, over six seeds: with trails that
  // never fade, the early long routes keep attracting ants.
  ai::GridMap map = twoGapMap();
  double with = 0, without = 0;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    with += runColony(map, withEvaporation(0.1, seed), 100).lastMean / 6;
    without += runColony(map, withEvaporation(0.0, seed), 100).lastMean / 6;
  }
  std::printf("optimum %.2f: mean route with evaporation %.2f, without %.2f\n", optimum(map), with,
              without);
  EXPECT_GT(without, 1.15 * with);
}

}  // namespace
}  // namespace zonesim::crowd
