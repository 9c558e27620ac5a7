// Formations: members hold their slots around a centre that A* routes across open ground
// (no member is ever taken for cut off), and a member standing behind a wall from the group
// plans an A* path around the wall, follows it and takes its slot again.

#include "crowd/formation.h"

#include <gtest/gtest.h>

namespace zonesim::crowd {
namespace {

const std::vector<Vec2> kSquare{{1, 1}, {1, -1}, {-1, 1}, {-1, -1}};

TEST(Formation, HoldsSlotsWhileTheCentreMoves) {
  ai::GridMap map(40, 40);
  FormationSettings s;
  Formation f(map, MapFrame{}, s, kSquare, Vec2{5.5, 20.5});
  std::vector<Vec2> pos, vel(4);
  for (int i = 0; i < 4; ++i) pos.push_back(f.slotPosition(i));
  ASSERT_TRUE(f.setDestination(Vec2{34.5, 30.5}));  // a diagonal leg turns the slots
  const double dt = 1.0 / 20;
  double worst = 0;
  int steps = 0;
  for (; steps < 2000 && !f.centreArrived(); ++steps) {
    f.step(pos, vel, dt);
    for (int i = 0; i < 4; ++i) worst = std::max(worst, length(pos[i] - f.slotPosition(i)));
  }
  for (int k = 0; k < 100; ++k) f.step(pos, vel, dt);  // settle at the destination
  std::printf("centre arrived after %.1f s, worst slot error on the way %.3f m\n", steps * dt,
              worst);
  EXPECT_TRUE(f.centreArrived());
  EXPECT_EQ(f.rejoinPlans(), 0);
  EXPECT_LT(worst, 1.5);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(f.mode(i), MemberMode::InFormation);
    EXPECT_LT(length(pos[i] - f.slotPosition(i)), 0.1);
  }
  EXPECT_LT(length(f.centre() - Vec2{34.5, 30.5}), 1e-9);
}

TEST(Formation, MemberCutOffByAWallPlansAStarAndRejoins) {
  // A wall at x = 15 from the top down to y = 16; the only way round is through rows 17-19.
  ai::GridMap map(30, 20);
  for (int y = 0; y < 17; ++y) map.setPassable(15, y, false);
  const MapFrame frame{};
  FormationSettings s;
  Formation f(map, frame, s, kSquare, Vec2{7.5, 5.5});
  std::vector<Vec2> pos, vel(4);
  for (int i = 0; i < 3; ++i) pos.push_back(f.slotPosition(i));
  const Vec2 start{22.5, 5.5};  // member 3: behind the wall
  pos.push_back(start);
  ASSERT_TRUE(f.setDestination(Vec2{7.5, 12.5}));
  const double dt = 1.0 / 20;
  bool wasRejoining = false;
  int blocked = 0, steps = 0;
  double travelled = 0;
  for (; steps < 1200; ++steps) {
    Vec2 before = pos[3];
    f.step(pos, vel, dt);
    travelled += length(pos[3] - before);
    wasRejoining = wasRejoining || f.mode(3) == MemberMode::Rejoining;
    for (Vec2 p : pos) blocked += !walkable(map, frame, p);
    if (f.centreArrived() && f.mode(3) == MemberMode::InFormation &&
        length(pos[3] - f.slotPosition(3)) < 0.1)
      break;
  }
  // The shortest way round: down the right side to the gap, through it, up to the group.
  ai::GridSearch search(map);
  ai::GridPath around;
  ASSERT_TRUE(search.findPath(frame.cellOf(start), frame.cellOf(f.slotPosition(3)), around));
  std::printf("rejoined after %.1f s, travelled %.1f m (A* around the wall %.1f m), %d plans\n",
              steps * dt, travelled, around.length, f.rejoinPlans());
  EXPECT_TRUE(wasRejoining);
  EXPECT_GE(f.rejoinPlans(), 1);
  EXPECT_EQ(f.mode(3), MemberMode::InFormation);
  EXPECT_LT(length(pos[3] - f.slotPosition(3)), 0.1);
  EXPECT_EQ(blocked, 0);
  // It went round the wall: at least the A* length less the diagonal shortcuts a continuous
  // mover takes (octile distance over-counts a straight slanted line by at most 8%).
  EXPECT_GT(travelled, 0.9 * around.length);
  EXPECT_LT(travelled, 1.6 * around.length);
}

}  // namespace
}  // namespace zonesim::crowd
