// One ant's trip by the colony rule (crowd/ant_trip_rule.h): the way home cuts detours but no
// blocked corner; a dead end is remembered and backed off from, one cell per decision, and at
// the nest forgotten; an ant past max_steps turns home laying nothing and counts no trip; one
// at the food lays Q / length on every cell of its way home and counts the trip there.

#include "crowd/ant_trip_rule.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace zonesim::crowd {
namespace {

AntTripSettings settings(int max_steps = 0) {
  return {AntChoice{}, 1.0, max_steps};
}

// 5x3: only the middle row is open, a corridor with no diagonal steps.
ai::GridMap corridor() {
  ai::GridMap map(5, 3);
  for (int x = 0; x < 5; ++x) {
    map.setPassable(x, 0, false);
    map.setPassable(x, 2, false);
  }
  return map;
}

TEST(AntTripRule, TheWayHomeStepsToTheEarliestRouteCellNextToIt) {
  ai::GridMap map(5, 5);
  AntTripRule rule(map, {0, 0}, {4, 4}, settings());
  std::vector<std::int32_t> route = {0, 0, 1, 0, 2, 0, 2, 1, 1, 1};
  rule.shorten(route);
  EXPECT_EQ(route, (std::vector<std::int32_t>{0, 0, 1, 1}));
  EXPECT_DOUBLE_EQ(routeLength(route), ai::kDiagonalCost);
}

TEST(AntTripRule, TheWayHomeCutsNoBlockedCorner) {
  ai::GridMap map(5, 5);
  map.setPassable(0, 1, false);  // (1, 1) to (0, 0) would cut this corner
  AntTripRule rule(map, {0, 0}, {4, 4}, settings());
  std::vector<std::int32_t> route = {0, 0, 1, 0, 2, 0, 2, 1, 1, 1};
  rule.shorten(route);
  EXPECT_EQ(route, (std::vector<std::int32_t>{0, 0, 1, 0, 1, 1}));
  EXPECT_DOUBLE_EQ(routeLength(route), 2.0);
}

TEST(AntTripRule, ADeadEndIsBackedOffOneCellAtATimeAndNotEnteredAgain) {
  ai::GridMap map = corridor();
  AntTripRule rule(map, {2, 1}, {4, 1}, settings());
  AntTrip trip;
  trip.route = {2, 1, 1, 1, 0, 1};  // it went west, into the corridor's end
  int draws = 0;
  auto uniform = [&](int) {
    ++draws;
    return 0.5;
  };
  auto trail = [](int, ai::Cell) { return 1.0; };
  EXPECT_EQ(rule.decide(trip, trail, uniform), AntDecision::BackedOff);
  EXPECT_EQ(trip.route, (std::vector<std::int32_t>{2, 1, 1, 1}));
  EXPECT_EQ(trip.dead_ends, (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(rule.decide(trip, trail, uniform), AntDecision::BackedOff);
  EXPECT_EQ(trip.route, (std::vector<std::int32_t>{2, 1}));
  EXPECT_EQ(trip.dead_ends, (std::vector<std::int32_t>{0, 1, 1, 1}));
  EXPECT_EQ(draws, 0);  // a dead end draws nothing
  EXPECT_FALSE(rule.open(trip, {1, 1}));
  EXPECT_TRUE(rule.open(trip, {3, 1}));
  EXPECT_EQ(rule.decide(trip, trail, uniform), AntDecision::Moved);  // east, the one way open
  EXPECT_EQ(trip.route, (std::vector<std::int32_t>{2, 1, 3, 1}));
  EXPECT_EQ(rule.target(trip), (ai::Cell{3, 1}));
}

TEST(AntTripRule, ADeadEndAtTheNestIsForgotten) {
  ai::GridMap map = corridor();
  AntTripRule rule(map, {0, 1}, {4, 1}, settings());
  AntTrip trip;
  trip.route = {0, 1};
  trip.dead_ends = {1, 1};
  auto trail = [](int, ai::Cell) { return 1.0; };
  auto uniform = [](int) { return 0.5; };
  EXPECT_EQ(rule.decide(trip, trail, uniform), AntDecision::StuckAtNest);
  EXPECT_EQ(trip.route, (std::vector<std::int32_t>{0, 1}));
  EXPECT_TRUE(trip.dead_ends.empty());
  EXPECT_EQ(rule.decide(trip, trail, uniform), AntDecision::Moved);
  EXPECT_EQ(trip.route, (std::vector<std::int32_t>{0, 1, 1, 1}));
}

TEST(AntTripRule, PastMaxStepsAnAntWalksHomeLayingNothing) {
  ai::GridMap map(6, 6);
  AntTripRule rule(map, {0, 0}, {5, 5}, settings(3));
  AntTrail trail(map, 0.01, 0.1, 1.0);
  auto uniform = [](int) { return 0.5; };
  AntTrip trip;
  trip.route = {0, 0, 1, 0, 2, 0, 3, 0};  // four cells: past max_steps
  AntArrival a = rule.arrive(trip, trail, true, uniform);
  EXPECT_EQ(a.cell, (ai::Cell{3, 0}));
  EXPECT_EQ(a.laid, 0);
  EXPECT_EQ(trip.mode, std::int32_t(AntMode::Returning));
  EXPECT_EQ(trip.route_length, 0.0);
  EXPECT_EQ(trip.route_at, 2);
  int arrivals = 1;
  do {
    a = rule.arrive(trip, trail, true, uniform);
    ++arrivals;
    EXPECT_EQ(a.laid, 0);
  } while (trip.mode == std::int32_t(AntMode::Returning));
  EXPECT_EQ(a.cell, (ai::Cell{0, 0}));
  EXPECT_EQ(a.trip_length, 0.0);  // no trip counted
  EXPECT_EQ(arrivals, 4);         // the turn, then (2, 0), (1, 0) and the nest
  EXPECT_EQ(trip.route, (std::vector<std::int32_t>{0, 0}));
}

TEST(AntTripRule, AtTheFoodAnAntLaysQOverLengthOnEveryCellHome) {
  ai::GridMap map(6, 6);
  AntTripRule rule(map, {0, 0}, {3, 0}, settings());
  AntTrail trail(map, 0.01, 0.1, 1.0);
  auto uniform = [](int) { return 0.5; };
  AntTrip trip;
  trip.route = {0, 0, 1, 1, 2, 1, 3, 0};  // nest, a detour through row 1, the food
  AntArrival a = rule.arrive(trip, trail, true, uniform);
  const std::int64_t units = trailDepositUnits(1.0, trip.route_length);
  EXPECT_EQ(a.cell, (ai::Cell{3, 0}));
  EXPECT_EQ(a.laid, units);
  EXPECT_EQ(trip.mode, std::int32_t(AntMode::Returning));
  EXPECT_DOUBLE_EQ(trip.route_length, 2 * ai::kDiagonalCost + 1);
  std::vector<ai::Cell> laid_on = {a.cell};
  do {
    a = rule.arrive(trip, trail, true, uniform);
    EXPECT_EQ(a.laid, units);
    laid_on.push_back(a.cell);
  } while (a.trip_length == 0);
  EXPECT_DOUBLE_EQ(a.trip_length, 2 * ai::kDiagonalCost + 1);
  EXPECT_EQ(laid_on, (std::vector<ai::Cell>{{3, 0}, {2, 1}, {1, 1}, {0, 0}}));
  // Home: a new trip from the nest.
  EXPECT_EQ(trip.mode, std::int32_t(AntMode::Searching));
  EXPECT_EQ(trip.route, (std::vector<std::int32_t>{0, 0}));
  EXPECT_EQ(trip.route_length, 0.0);
}

TEST(AntTripRule, OnceTheFoodIsGoneAnAntAtItsCellKeepsSearching) {
  ai::GridMap map(6, 6);
  AntTripRule rule(map, {0, 0}, {1, 0}, settings());
  AntTrail trail(map, 0.01, 0.1, 1.0);
  AntTrip trip;
  trip.route = {0, 0, 1, 0};
  const AntArrival a = rule.arrive(trip, trail, false, [](int) { return 0.5; });
  EXPECT_EQ(a.laid, 0);
  EXPECT_EQ(trip.mode, std::int32_t(AntMode::Searching));
  EXPECT_EQ(routeCellCount(trip.route), 3);
}

TEST(AntTripRule, ANestOnAWallIsAClearError) {
  ai::GridMap map = corridor();
  try {
    AntTripRule rule(map, {0, 0}, {4, 1}, settings());
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "AntTripRule: nest and food must be walkable");
  }
}

}  // namespace
}  // namespace zonesim::crowd
