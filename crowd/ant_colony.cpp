#include "crowd/ant_colony.h"

#include <cmath>
#include <stdexcept>

#include "ai/grid_path.h"
#include "crowd/grid_step.h"

namespace zonesim::crowd {

namespace {
int directionOf(ai::Cell a, ai::Cell b) {
  for (int k = 0; k < 8; ++k)
    if (gridStep(a, k) == b) return k;
  return -1;
}

// The trip rule's settings, once the nest and food are checked (the colony's error first).
AntTripSettings tripSettings(const ai::GridMap& map, ai::Cell nest, ai::Cell food,
                             const AntColonySettings& settings) {
  if (!map.passable(nest.x, nest.y) || !map.passable(food.x, food.y))
    throw std::invalid_argument("AntColony: nest and food must be walkable");
  return {{settings.alpha, settings.beta, settings.knows_food_position, settings.exploitation},
          settings.deposit,
          settings.max_steps};
}

}  // namespace

AntColony::AntColony(const ai::GridMap& map, ai::Cell nest, ai::Cell food,
                     const AntColonySettings& settings)
    : map_(map),
      nest_(nest),
      food_(food),
      settings_(settings),
      trips_(map, nest, food, tripSettings(map, nest, food, settings)),
      rng_(settings.seed, 0xA17),
      tau_(std::size_t(map.width()) * map.height() * 8, settings.initial_pheromone),
      seen_(std::size_t(map.width()) * map.height(), 0) {
  if (settings_.max_steps <= 0) settings_.max_steps = 4 * map.passableCount();
}

bool AntColony::walk(AntTrip& trip) {
  // A stamp per cell says what the trip's route and dead ends say, without searching them.
  ++stamp_;
  auto mark = [&](ai::Cell n) { seen_[std::size_t(map_.index(n.x, n.y))] = stamp_; };
  trips_.restart(trip);
  mark(nest_);
  for (int moves = 0; moves < settings_.max_steps; ++moves) {
    const ai::Cell c = trips_.target(trip);
    if (c == food_) return true;
    const std::size_t from = std::size_t(map_.index(c.x, c.y)) * 8;
    const AntDecision d = trips_.decide(
        trip, [&](int step, ai::Cell) { return tau_[from + step]; },
        [&](ai::Cell n) { return seen_[std::size_t(map_.index(n.x, n.y))] != stamp_; },
        [&](int) { return rng_.uniform(); });
    if (d == AntDecision::Moved) mark(trips_.target(trip));
    // A dead end at the nest: this ant is lost.
    if (d == AntDecision::StuckAtNest) return false;
  }
  return trips_.target(trip) == food_;
}

AntIteration AntColony::iterate() {
  AntIteration out;
  routes_.resize(std::size_t(settings_.ants));
  double sum = 0;
  for (int a = 0; a < settings_.ants; ++a) {
    std::vector<ai::Cell>& route = routes_[a];
    if (!walk(trip_)) {
      route.clear();
      continue;
    }
    route = routeCells(trip_.route);
    double len = ai::pathLength(route);
    ++out.found;
    sum += len;
    if (best_length_ == 0 || len < best_length_) {
      best_length_ = len;
      best_ = route;
    }
  }
  for (double& t : tau_) t = std::max(settings_.min_pheromone, t * (1.0 - settings_.evaporation));
  auto lay = [&](const std::vector<ai::Cell>& route, double amount) {
    for (std::size_t k = 0; k + 1 < route.size(); ++k) {
      int dir = directionOf(route[k], route[k + 1]);
      tau_[std::size_t(map_.index(route[k].x, route[k].y)) * 8 + dir] += amount;
    }
  };
  for (const auto& route : routes_)
    if (!route.empty()) lay(route, settings_.deposit / ai::pathLength(route));
  if (settings_.elite_deposit && !best_.empty()) lay(best_, settings_.deposit / best_length_);
  out.mean_length = out.found ? sum / out.found : 0.0;
  out.best_length = best_length_;
  return out;
}

bool AntColony::trailRoute(std::vector<ai::Cell>& out) const {
  return strongestTrailRoute(
      map_, nest_, food_, [&](ai::Cell c, int k, ai::Cell) { return pheromone(c, k); }, out);
}

}  // namespace zonesim::crowd
