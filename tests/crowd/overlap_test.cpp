// Overlap measurement: hand-placed agents with known overlaps (exact in binary) give exactly
// the deepest overlap, the closest pair's ids and the number of overlapping pairs; touching
// discs do not overlap, ghosts count against owned agents but not among themselves, and on
// random crowds the grid's answer equals brute force for several cell sizes.

#include "crowd/overlap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

#include "common/rng.h"
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

}  // namespace
}  // namespace zonesim::crowd
