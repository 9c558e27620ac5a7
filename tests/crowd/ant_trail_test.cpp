// The fixed-point trail of the zone's ant colonies (crowd/ant_trail.h): evaporation is exact
// integer arithmetic (rounding down, never below one unit) within one unit a tick of the
// analytic (1 - rho)^t; deposits are Q / length in units with a floor of one; the strongest
// route follows the trail laid; bad input is a clear error.

#include "crowd/ant_trail.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace zonesim::crowd {
namespace {

TEST(AntTrail, WithoutEvaporationTheTrailNeverChanges) {
  ai::GridMap map(4, 4);
  AntTrail trail(map, 0.01, 0.0, 0.05);
  EXPECT_EQ(trail.keep(), std::uint64_t(1) << 32);
  const std::vector<std::int64_t> none(trail.size(), 0);
  for (int t = 0; t < 1000; ++t) trail.evaporateAndAdd(none);
  EXPECT_EQ(trail.units({2, 3}), std::llround(0.01 * kTrailScale));
  EXPECT_EQ(trail.total(), 16 * double(std::llround(0.01 * kTrailScale)) / kTrailScale);
}

TEST(AntTrail, HalvingEvaporationHalvesExactlyDownToOneUnit) {
  // keep = 1/2 per tick is exact in 32.32: one pheromone (2^20 units) halves to one unit in
  // 20 ticks and stays there.
  ai::GridMap map(2, 2);
  AntTrail trail(map, 1.0, 0.5, 1.0);
  EXPECT_EQ(trail.keep(), std::uint64_t(1) << 31);
  const std::vector<std::int64_t> none(trail.size(), 0);
  for (int t = 1; t <= 22; ++t) {
    trail.evaporateAndAdd(none);
    EXPECT_EQ(trail.units({1, 1}), t <= 20 ? std::int64_t(1) << (20 - t) : 1) << "tick " << t;
  }
}

TEST(AntTrail, EvaporationRoundsDownByUnderOneUnitATick) {
  ai::GridMap map(3, 3);
  const double rho = 0.05, dt = 0.05;
  AntTrail trail(map, 10.0, rho, dt);
  EXPECT_EQ(trail.keep(), std::uint64_t(std::llround(std::pow(1 - rho, dt) * 0x1.0p32)));
  const std::vector<std::int64_t> none(trail.size(), 0);
  std::int64_t expected = std::llround(10.0 * kTrailScale);
  const int ticks = 600;
  for (int t = 0; t < ticks; ++t) {
    trail.evaporateAndAdd(none);
    expected = std::int64_t((unsigned __int128)std::uint64_t(expected) * trail.keep() >> 32);
  }
  EXPECT_EQ(trail.units({0, 2}), expected);
  const double analytic = 10.0 * std::pow(1 - rho, ticks * dt);
  EXPECT_NEAR(trail.at({0, 2}), analytic, ticks / kTrailScale);
  EXPECT_LT(trail.at({0, 2}), 0.3 * 10.0);  // it did evaporate: (0.95)^30 = 0.21
}

TEST(AntTrail, DeltasAreAddedAfterTheTicksEvaporation) {
  ai::GridMap map(3, 1);
  AntTrail trail(map, 1.0, 0.5, 1.0);
  std::vector<std::int64_t> deltas(trail.size(), 0);
  deltas[trail.index({2, 0})] = 1000;
  trail.evaporateAndAdd(deltas);
  EXPECT_EQ(trail.units({2, 0}), (std::int64_t(1) << 19) + 1000);
  EXPECT_EQ(trail.units({1, 0}), std::int64_t(1) << 19);
}

TEST(AntTrail, ADepositIsQOverLengthWithAFloorOfOneUnit) {
  EXPECT_EQ(trailDepositUnits(1.0, 10.0), std::llround(kTrailScale / 10));
  EXPECT_EQ(trailDepositUnits(2.0, 1.0), std::int64_t(1) << 21);
  EXPECT_EQ(trailDepositUnits(1e-9, 1000.0), 1);
  // A tiny initial trail is one unit too, so that no cell is ever without trail.
  ai::GridMap map(1, 1);
  EXPECT_EQ(AntTrail(map, 1e-12, 0.1, 1.0).units({0, 0}), 1);
}

TEST(AntTrail, TheStrongestRouteFollowsTheTrailLaid) {
  ai::GridMap map(3, 3);
  AntTrail trail(map, 0.01, 0.0, 1.0);
  std::vector<std::int64_t> deltas(trail.size(), 0);
  deltas[trail.index({1, 1})] = deltas[trail.index({2, 2})] = 5000;
  trail.evaporateAndAdd(deltas);
  const std::vector<ai::Cell> route = trail.strongestRoute({0, 0}, {2, 2});
  ASSERT_EQ(route.size(), 3u);
  EXPECT_EQ(route[1], (ai::Cell{1, 1}));
  EXPECT_EQ(route[2], (ai::Cell{2, 2}));
}

TEST(AntTrail, NoStrongestRouteToFoodBehindWalls) {
  ai::GridMap map(3, 3);
  map.setPassable(1, 1, false);
  map.setPassable(1, 2, false);
  map.setPassable(2, 1, false);
  AntTrail trail(map, 0.01, 0.1, 1.0);
  EXPECT_TRUE(trail.strongestRoute({0, 0}, {2, 2}).empty());
}

TEST(AntTrail, BadInputIsAClearError) {
  ai::GridMap map(2, 2);
  try {
    AntTrail(map, 0.01, 1.5, 1.0);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "AntTrail: evaporation 1.500000 is not a fraction in [0, 1]");
  }
  AntTrail trail(map, 0.01, 0.1, 1.0);
  try {
    trail.evaporateAndAdd(std::vector<std::int64_t>(3, 0));
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "AntTrail: 3 deltas for 4 cells");
  }
}

}  // namespace
}  // namespace zonesim::crowd
