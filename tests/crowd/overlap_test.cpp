// Overlap measurement: hand-placed agents with known overlaps (exact in binary) give exactly
// the deepest overlap, the closest pair's ids and the number of overlapping pairs; touching
// discs do not overlap, ghosts count against owned agents but not among themselves, and on
// random crowds the grid's answer equals brute force for several cell sizes. Two groups of a
// flow crowd crossing each other's path overlap by far more than 1 cm with the default
// settings, and by at most 1 cm with the bounding settings of docs/benchmarks.md (issue 18).

#include "crowd/overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "common/rng.h"
#include "crowd/flow_crowd.h"
#include "crowd_test_util.h"

namespace zonesim::crowd {
namespace {

// Radius 0.375: overlapping pairs at 0.5 m (0.25 deep) and 0.625 m (0.125 deep), a touching
// pair at 0.75 m and a loner.
test::AgentArrays handPlaced() {
  test::AgentArrays a;
  a.add(7, Vec2{0.0, 0.0}, Vec2{});
  a.add(3, Vec2{0.5, 0.0}, Vec2{});
  a.add(11, Vec2{3.0, 0.0}, Vec2{});
  a.add(5, Vec2{3.375, 0.5}, Vec2{});
  a.add(20, Vec2{10.0, 10.0}, Vec2{});
  a.add(21, Vec2{10.75, 10.0}, Vec2{});
  a.add(30, Vec2{-20.0, 4.0}, Vec2{});
  return a;
}

TEST(Overlap, HandPlacedAgentsGiveTheExactDeepestOverlapAndPairCount) {
  test::AgentArrays a = handPlaced();
  for (double cell : {0.75, 1.0, 2.0, 8.0}) {
    NeighbourGrid grid;
    grid.build(a.span(), {}, cell);
    const Overlap o = deepestOverlap(grid, 0.375);
    EXPECT_EQ(o.depth, 0.25) << "cell " << cell;
    EXPECT_EQ(o.a, 3u);
    EXPECT_EQ(o.b, 7u);
    EXPECT_EQ(o.pairs, 2u);
  }
}

TEST(Overlap, SeparatedOrTouchingAgentsDoNotOverlap) {
  test::AgentArrays a;
  a.add(1, Vec2{0.0, 0.0}, Vec2{});
  a.add(2, Vec2{0.75, 0.0}, Vec2{});
  a.add(3, Vec2{0.0, 0.75}, Vec2{});
  NeighbourGrid grid;
  grid.build(a.span(), {}, 1.0);
  const Overlap o = deepestOverlap(grid, 0.375);
  EXPECT_EQ(o.depth, 0.0);
  EXPECT_EQ(o.pairs, 0u);
  EXPECT_EQ(o.a, 0u);
  EXPECT_THROW(deepestOverlap(grid, 0.0), std::invalid_argument);
}

TEST(Overlap, GhostsCountAgainstOwnedAgentsButNotAmongThemselves) {
  test::AgentArrays a = handPlaced();
  test::AgentArrays ghosts;
  ghosts.add(100, Vec2{10.0, 10.5}, Vec2{});    // 0.5 m from owned 20: 0.25 deep
  ghosts.add(101, Vec2{-20.0, 3.875}, Vec2{});  // 0.125 m from owned 30: 0.625 deep
  ghosts.add(102, Vec2{50.0, 50.0}, Vec2{});
  ghosts.add(103, Vec2{50.0, 50.0}, Vec2{});  // a ghost pair on one spot: the owner's
  NeighbourGrid grid;
  grid.build(a.span(), ghosts.ghosts(), 1.0);
  const Overlap o = deepestOverlap(grid, 0.375);
  EXPECT_EQ(o.depth, 0.625);
  EXPECT_EQ(o.a, 30u);
  EXPECT_EQ(o.b, 101u);
  EXPECT_EQ(o.pairs, 4u);
}

TEST(Overlap, RandomCrowdsMatchBruteForce) {
  Pcg32 rng(9, 4);
  test::AgentArrays a;
  for (int i = 0; i < 600; ++i)
    a.add(std::uint64_t(i) * 2654435761ULL + 1, Vec2{rng.uniform(-10, 10), rng.uniform(-10, 10)},
          Vec2{});
  const double radius = 0.3;
  double closest = 1e300;
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < a.pos.size(); ++i)
    for (std::size_t j = i + 1; j < a.pos.size(); ++j) {
      const double d = length(a.pos[i] - a.pos[j]);
      closest = std::min(closest, d);
      pairs += d < 2 * radius;
    }
  ASSERT_GT(pairs, 10u);  // 600 agents on 400 m^2 overlap somewhere
  for (double cell : {0.6, 1.0, 2.0, 3.0}) {
    NeighbourGrid grid;
    grid.build(a.span(), {}, cell);
    const Overlap o = deepestOverlap(grid, radius);
    EXPECT_EQ(o.pairs, pairs) << "cell " << cell;
    EXPECT_DOUBLE_EQ(o.depth, 2 * radius - closest) << "cell " << cell;
  }
}

struct CrossingRun {
  double deepest = 0;  // m, over every step, bodies of 0.3 m
  int arrived = 0;
  int crossed = 0;  // agents past the middle line, toward their goal, at the end
};

// 24x24 open cells; 100 agents on a 1 m lattice in the west head east, 100 in the south head
// north, for 20 s: the groups cross in the middle (no overlap at the start).
CrossingRun crossing(const FlowCrowdSettings& s) {
  ai::GridMap map(24, 24);
  FlowCrowd crowd(map, MapFrame{}, s);
  const int east = crowd.addDestination(ai::Cell{22, 12});
  const int north = crowd.addDestination(ai::Cell{12, 22});
  test::AgentArrays a;
  std::vector<std::uint16_t> dest;
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      a.add(a.ids.size() + 1, Vec2{1.5 + x, 12.5 + y}, Vec2{});
      dest.push_back(std::uint16_t(east));
      a.add(a.ids.size() + 1, Vec2{7.5 + y, 1.5 + x}, Vec2{});
      dest.push_back(std::uint16_t(north));
    }
  std::vector<std::uint8_t> arrived(a.ids.size(), 0);
  CrossingRun r;
  for (int k = 0; k < 600; ++k) {
    crowd.step(a.span(), dest, arrived, {}, 1.0 / 30);
    r.deepest = std::max(r.deepest, deepestOverlap(crowd.grid(), 0.3).depth);
  }
  for (std::size_t i = 0; i < a.ids.size(); ++i) {
    r.arrived += arrived[i];
    r.crossed += arrived[i] || (dest[i] == east ? a.pos[i].x > 12 : a.pos[i].y > 12);
  }
  return r;
}

TEST(Overlap, CrossingFlowsOverlapByAtMostOneCentimetreWithTheBoundingSettings) {
  const CrossingRun loose = crossing(FlowCrowdSettings{});
  EXPECT_GT(loose.deepest, 0.01);  // the defaults let the groups pass through each other
  FlowCrowdSettings bounded;
  bounded.separation_radius = 0.8;
  bounded.separation_weight = 1000;
  bounded.max_force = 100;
  const CrossingRun tight = crossing(bounded);
  EXPECT_LE(tight.deepest, 0.01);
  // Not by standing still: nearly all of them get past the middle (194 of 200 when written),
  // fewer reach the goal cell within 20 s (53 against 199: the price of the bound).
  EXPECT_GE(tight.crossed, 180);
  EXPECT_GE(loose.crossed, 180);
  EXPECT_GT(tight.arrived, 0);
  std::printf(
      "crossing: deepest overlap %.4f m (defaults) and %.4f m (bounded); arrived %d and %d; "
      "crossed %d and %d\n",
      loose.deepest, tight.deepest, loose.arrived, tight.arrived, loose.crossed, tight.crossed);
}

}  // namespace
}  // namespace zonesim::crowd
