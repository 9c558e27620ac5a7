// Bodies kept apart (crowd/keep_apart.h): a free move is kept as it is; a move toward a
// neighbour stops half the gap short and slides along it; an overlap is backed off by half its
// depth; a squeezed agent keeps every gap and deepens no overlap; two agents at one point back
// off opposite ways. Over random crowds in which every agent solves from the same start, no
// pair ends closer than 2 radius unless it started closer, and then no closer than it started
// (brute force over every pair).

#include "crowd/keep_apart.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "common/rng.h"

namespace zonesim::crowd {
namespace {

TEST(KeepApart, AFreeMoveIsKeptExactly) {
  KeepApart k;
  k.begin(0.3, 0.1);
  k.neighbour({0.9, 0.0}, true);  // gap 0.3: more than twice the reach, cannot bind
  EXPECT_TRUE(k.planes().empty());
  k.neighbour({0.0, 0.75}, true);  // gap 0.15: kept, but the move goes away from it
  ASSERT_EQ(k.planes().size(), 1u);
  const Vec2 wish{0.0625, -0.03125};
  EXPECT_EQ(k.solve(wish), wish);
  EXPECT_NEAR(k.queryRadius(), 0.8, 1e-15);
}

TEST(KeepApart, ALoneAgentJustPastItsReachIsClampedNotSentSideways) {
  KeepApart k;
  k.begin(0.3, 0.1);
  const Vec2 wish{0.1 * (1 + 1e-15), 0.0};  // the speed clamp's rounding can leave this
  const Vec2 x = k.move(wish);
  EXPECT_NEAR(x.x, 0.1, 1e-15);
  EXPECT_EQ(x.y, 0.0);
}

TEST(KeepApart, AMoveTowardANeighbourStopsHalfTheGapShortAndSlidesAlongIt) {
  KeepApart k;
  k.begin(0.25, 0.5);
  k.neighbour({0.75, 0.0}, true);  // gap 0.25: this agent may take 0.125 of it
  const Vec2 x = k.solve({0.5, 0.25});
  EXPECT_DOUBLE_EQ(x.x, 0.125);
  EXPECT_DOUBLE_EQ(x.y, 0.25);  // the sideways part of the wish is kept
  EXPECT_TRUE(k.keeps(x));
  EXPECT_FALSE(k.keeps({0.25, 0.0}));
}

TEST(KeepApart, AHeldBackMoveStepsAsideThoughThePlainMoveIsNearerTheWish) {
  // Head-on: the plain solution stops half the gap short on the line between the two, and is
  // by construction the nearest move to the wish that keeps the gap. The sidestep ends
  // farther from the wish on purpose: it is what lets two agents pass instead of pressing on
  // that line for ever. Keeping the nearer of the two would never sidestep (measured, 5
  // December: 242 instead of 357 of the courtyard's 400 NPCs arrive in 130 s).
  KeepApart k;
  k.begin(0.25, 0.25);
  k.neighbour({0.75, 0.0}, true);  // gap 0.25: this agent may take 0.125 of it
  const Vec2 wish{0.25, 0.0};
  const Vec2 plain = k.solve(wish);
  EXPECT_DOUBLE_EQ(plain.x, 0.125);  // the whole half gap, and nothing sideways
  EXPECT_EQ(plain.y, 0.0);
  const Vec2 x = k.move(wish);
  EXPECT_EQ(x, k.solve(wish + Vec2{wish.y, -wish.x} * 3.0));
  EXPECT_LT(x.y, 0.0);  // to its right
  EXPECT_GT(x.x, 0.0);  // still forward
  EXPECT_TRUE(k.keeps(x));
  EXPECT_GT(lengthSq(x - wish), lengthSq(plain - wish));
}

TEST(KeepApart, AnOverlapIsBackedOffByHalfItsDepth) {
  KeepApart k;
  k.begin(0.25, 0.5);
  k.neighbour({0.0, 0.25}, true);  // 0.25 deep: back off 0.125 along -y
  const Vec2 x = k.solve({});
  EXPECT_DOUBLE_EQ(x.x, 0.0);
  EXPECT_DOUBLE_EQ(x.y, -0.125);
}

TEST(KeepApart, ASqueezedAgentKeepsEveryGapAndDeepensNoOverlap) {
  KeepApart k;
  k.begin(0.25, 0.5);
  k.neighbour({0.25, 0.0}, true);   // overlaps on the right...
  k.neighbour({-0.25, 0.0}, true);  // ...and on the left: no move backs off from both
  k.neighbour({0.0, 0.625}, true);  // and a gap of 0.125 above
  const Vec2 x = k.solve({0.5, 0.5});
  EXPECT_DOUBLE_EQ(x.x, 0.0);     // neither overlap deepens
  EXPECT_DOUBLE_EQ(x.y, 0.0625);  // the gap above is kept
  EXPECT_TRUE(k.keeps(x));
}

TEST(KeepApart, TwoAgentsAtOnePointBackOffOppositeWays) {
  KeepApart first, second;
  first.begin(0.25, 0.5);
  second.begin(0.25, 0.5);
  first.neighbour({}, true);
  second.neighbour({}, false);
  EXPECT_DOUBLE_EQ(first.solve({}).x, -0.25);
  EXPECT_DOUBLE_EQ(second.solve({}).x, 0.25);
}

TEST(KeepApart, RandomCrowdsMakeNoNewOverlapAndDeepenNone) {
  const double radius = 0.3, reach = 0.2;
  int squeezed = 0, bound = 0, overlapping = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Pcg32 rng(seed, 3);
    std::vector<Vec2> pos(400), moved(400);
    for (Vec2& p : pos) p = {rng.uniform(0.0, 20.0), rng.uniform(0.0, 20.0)};
    KeepApart k;
    for (std::size_t i = 0; i < pos.size(); ++i) {
      k.begin(radius, reach);
      for (std::size_t j = 0; j < pos.size(); ++j)
        if (j != i && length(pos[j] - pos[i]) < k.queryRadius())
          k.neighbour(pos[j] - pos[i], i < j);
      const Vec2 wish{rng.uniform(-reach, reach), rng.uniform(-reach, reach)};
      const Vec2 x = k.solve(wish);
      EXPECT_TRUE(k.keeps(x));
      EXPECT_LE(length(x), reach * (1 + 1e-12));
      bound += !(x == clampLength(wish, reach));
      squeezed += std::any_of(k.planes().begin(), k.planes().end(),
                              [&](const GapPlane& p) { return dot(x, p.normal) > p.offset; });
      moved[i] = pos[i] + x;
    }
    for (std::size_t i = 0; i < pos.size(); ++i)
      for (std::size_t j = i + 1; j < pos.size(); ++j) {
        const double before = length(pos[j] - pos[i]), after = length(moved[j] - moved[i]);
        overlapping += before < 2 * radius;
        EXPECT_GE(after, std::min(before, 2 * radius) - 1e-12)
            << "seed " << seed << " pair " << i << ", " << j;
      }
  }
  // The crowds are dense enough to test something: many moves are bound, some agents are
  // squeezed between overlaps, and many pairs start overlapping.
  EXPECT_GT(bound, 2000);
  EXPECT_GT(squeezed, 50);
  EXPECT_GT(overlapping, 1000);
  std::printf("keep apart: %d of 8000 moves bound, %d squeezed, %d pairs overlapping at start\n",
              bound, squeezed, overlapping);
}

}  // namespace
}  // namespace zonesim::crowd
