#include "crowd/ant_trip_rule.h"

#include <algorithm>
#include <stdexcept>

namespace zonesim::crowd {

namespace {

bool contains(const std::vector<std::int32_t>& cells, ai::Cell c) {
  for (std::size_t k = 0; k + 1 < cells.size(); k += 2)
    if (cells[k] == c.x && cells[k + 1] == c.y) return true;
  return false;
}

}  // namespace

std::vector<ai::Cell> routeCells(const std::vector<std::int32_t>& cells) {
  std::vector<ai::Cell> out;
  out.reserve(std::size_t(routeCellCount(cells)));
  for (std::int32_t k = 0; k < routeCellCount(cells); ++k) out.push_back(routeCell(cells, k));
  return out;
}

double routeLength(const std::vector<std::int32_t>& route) {
  double length = 0;
  for (std::int32_t k = 1; k < routeCellCount(route); ++k)
    length += ai::octileDistance(routeCell(route, k - 1), routeCell(route, k));
  return length;
}

AntTripRule::AntTripRule(const ai::GridMap& map, ai::Cell nest, ai::Cell food,
                         const AntTripSettings& settings)
    : map_(map),
      nest_(nest),
      food_(food),
      choice_(settings.choice),
      deposit_(settings.deposit),
      max_steps_(settings.max_steps > 0 ? settings.max_steps : 4 * map.passableCount()) {
  if (!map.passable(nest.x, nest.y) || !map.passable(food.x, food.y))
    throw std::invalid_argument("AntTripRule: nest and food must be walkable");
}

void AntTripRule::begin(AntTrip& trip) const {
  if (trip.route.empty()) trip.route = {nest_.x, nest_.y};
}

ai::Cell AntTripRule::target(const AntTrip& trip) const {
  return trip.mode == std::int32_t(AntMode::Returning)
             ? routeCell(trip.route, trip.route_at)
             : routeCell(trip.route, routeCellCount(trip.route) - 1);
}

bool AntTripRule::open(const AntTrip& trip, ai::Cell n) const {
  return !contains(trip.route, n) && !contains(trip.dead_ends, n);
}

AntDecision AntTripRule::backOff(AntTrip& trip) const {
  if (routeCellCount(trip.route) > 1) {
    const ai::Cell c = routeCell(trip.route, routeCellCount(trip.route) - 1);
    trip.dead_ends.push_back(c.x);
    trip.dead_ends.push_back(c.y);
    trip.route.resize(trip.route.size() - 2);
    return AntDecision::BackedOff;
  }
  trip.dead_ends.clear();
  return AntDecision::StuckAtNest;
}

void AntTripRule::turnHome(AntTrip& trip, bool found) const {
  shorten(trip.route);
  const double length = routeLength(trip.route);
  trip.mode = std::int32_t(AntMode::Returning);
  trip.route_length = found ? length : 0;
  trip.route_at = std::max(0, routeCellCount(trip.route) - 2);
}

bool AntTripRule::stepHome(AntTrip& trip) const {
  if (trip.route_at > 0) {
    --trip.route_at;
    return false;
  }
  restart(trip);
  return true;
}

void AntTripRule::restart(AntTrip& trip) const {
  trip.mode = std::int32_t(AntMode::Searching);
  trip.route.assign({nest_.x, nest_.y});
  trip.dead_ends.clear();
  trip.route_length = 0;
  trip.route_at = 0;
}

bool AntTripRule::adjacent(ai::Cell a, ai::Cell b) const {
  for (int k = 0; k < 8; ++k)
    if (gridStep(a, k) == b) return gridStepAllowed(map_, a, k);
  return false;
}

void AntTripRule::shorten(std::vector<std::int32_t>& route) const {
  std::vector<std::int32_t> back;
  std::int32_t at = routeCellCount(route) - 1;
  back.insert(back.end(), {route[std::size_t(2 * at)], route[std::size_t(2 * at + 1)]});
  while (at > 0) {
    std::int32_t j = 0;
    while (j < at - 1 && !adjacent(routeCell(route, at), routeCell(route, j))) ++j;
    at = j;
    back.insert(back.end(), {route[std::size_t(2 * at)], route[std::size_t(2 * at + 1)]});
  }
  route.clear();
  for (std::size_t k = back.size(); k >= 2; k -= 2)
    route.insert(route.end(), {back[k - 2], back[k - 1]});
}

}  // namespace zonesim::crowd
