#include "crowd/ant_colony.h"

#include <cmath>
#include <stdexcept>

#include "ai/grid_path.h"

namespace zonesim::crowd {

namespace {
constexpr int kSteps[8][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {1, 1}, {-1, 1}, {-1, -1}, {1, -1}};

int directionOf(ai::Cell a, ai::Cell b) {
  for (int k = 0; k < 8; ++k)
    if (a.x + kSteps[k][0] == b.x && a.y + kSteps[k][1] == b.y) return k;
  return -1;
}
}  // namespace

AntColony::AntColony(const ai::GridMap& map, ai::Cell nest, ai::Cell food,
                     const AntColonySettings& settings)
    : map_(map),
      nest_(nest),
      food_(food),
      settings_(settings),
      rng_(settings.seed, 0xA17),
      tau_(std::size_t(map.width()) * map.height() * 8, settings.initialPheromone),
      seen_(std::size_t(map.width()) * map.height(), 0) {
  if (!map.passable(nest.x, nest.y) || !map.passable(food.x, food.y))
    throw std::invalid_argument("AntColony: nest and food must be walkable");
  if (settings_.maxSteps <= 0) settings_.maxSteps = 4 * map.passableCount();
}

bool AntColony::stepAllowed(int x, int y, int k) const {
  int nx = x + kSteps[k][0], ny = y + kSteps[k][1];
  if (!map_.passable(nx, ny)) return false;
  if (k >= 4 && (!map_.passable(nx, y) || !map_.passable(x, ny))) return false;
  return true;
}

bool AntColony::walk(std::vector<ai::Cell>& route) {
  ++stamp_;
  route.clear();
  route.push_back(nest_);
  seen_[map_.index(nest_.x, nest_.y)] = stamp_;
  double weight[8];
  for (int moves = 0; moves < settings_.maxSteps; ++moves) {
    ai::Cell c = route.back();
    if (c == food_) return true;
    double total = 0, strongest = -1;
    int strongestK = -1;
    for (int k = 0; k < 8; ++k) {
      weight[k] = 0;
      if (!stepAllowed(c.x, c.y, k)) continue;
      ai::Cell nc{c.x + kSteps[k][0], c.y + kSteps[k][1]};
      int n = map_.index(nc.x, nc.y);
      if (seen_[n] == stamp_) continue;
      double tau = tau_[std::size_t(map_.index(c.x, c.y)) * 8 + k];
      double step = k >= 4 ? ai::kDiagonalCost : 1.0;
      double eta =
          settings_.knowsFoodPosition ? 1.0 / (step + ai::octileDistance(nc, food_)) : 1.0 / step;
      weight[k] = std::pow(tau, settings_.alpha) * std::pow(eta, settings_.beta);
      total += weight[k];
      if (weight[k] > strongest) {
        strongest = weight[k];
        strongestK = k;
      }
    }
    if (strongestK < 0) {
      // Dead end: back off one cell (it stays marked, so the ant will not return).
      route.pop_back();
      if (route.empty()) return false;
      continue;
    }
    int chosen = strongestK;
    if (rng_.uniform() >= settings_.exploitation) {
      double pick = rng_.uniform() * total;
      for (int k = 0; k < 8; ++k) {
        if (weight[k] <= 0) continue;
        chosen = k;
        pick -= weight[k];
        if (pick < 0) break;
      }
    }
    ai::Cell n{c.x + kSteps[chosen][0], c.y + kSteps[chosen][1]};
    seen_[map_.index(n.x, n.y)] = stamp_;
    route.push_back(n);
  }
  return route.back() == food_;
}

AntIteration AntColony::iterate() {
  AntIteration out;
  routes_.resize(std::size_t(settings_.ants));
  double sum = 0;
  for (int a = 0; a < settings_.ants; ++a) {
    std::vector<ai::Cell>& route = routes_[a];
    if (!walk(route)) {
      route.clear();
      continue;
    }
    double len = ai::pathLength(route);
    ++out.found;
    sum += len;
    if (bestLength_ == 0 || len < bestLength_) {
      bestLength_ = len;
      best_ = route;
    }
  }
  for (double& t : tau_) t = std::max(settings_.minPheromone, t * (1.0 - settings_.evaporation));
  auto lay = [&](const std::vector<ai::Cell>& route, double amount) {
    for (std::size_t k = 0; k + 1 < route.size(); ++k) {
      int dir = directionOf(route[k], route[k + 1]);
      tau_[std::size_t(map_.index(route[k].x, route[k].y)) * 8 + dir] += amount;
    }
  };
  for (const auto& route : routes_)
    if (!route.empty()) lay(route, settings_.deposit / ai::pathLength(route));
  if (settings_.eliteDeposit && !best_.empty()) lay(best_, settings_.deposit / bestLength_);
  out.meanLength = out.found ? sum / out.found : 0.0;
  out.bestLength = bestLength_;
  return out;
}

bool AntColony::trailRoute(std::vector<ai::Cell>& out) const {
  std::vector<std::uint8_t> visited(seen_.size(), 0);
  out.assign(1, nest_);
  visited[map_.index(nest_.x, nest_.y)] = 1;
  while (!(out.back() == food_)) {
    ai::Cell c = out.back();
    int bestK = -1;
    double bestTau = -1;
    for (int k = 0; k < 8; ++k) {
      if (!stepAllowed(c.x, c.y, k)) continue;
      if (visited[map_.index(c.x + kSteps[k][0], c.y + kSteps[k][1])]) continue;
      double t = pheromone(c, k);
      if (t > bestTau) {
        bestTau = t;
        bestK = k;
      }
    }
    if (bestK < 0) return false;
    ai::Cell n{c.x + kSteps[bestK][0], c.y + kSteps[bestK][1]};
    visited[map_.index(n.x, n.y)] = 1;
    out.push_back(n);
  }
  return true;
}

}  // namespace zonesim::crowd
