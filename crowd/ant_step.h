#pragma once
// One ant's step on a grid, the rule that both colonies follow: AntColony (crowd/ant_colony.h)
// and the zone's ants, through crowd/ant_trip_rule.h (zone_node/systems/ant_movement.h only
// adapts entities to it). The ant senses the eight cells next to it, weighs each open one it
// has not walked this trip by trail^alpha * eta^beta and takes the strongest outright with
// probability `exploitation`, else draws one in proportion to its weight (the ACS rule). Where
// the trail lives (per directed step or per cell, double or fixed point: crowd/ant_trail.h)
// and where the draws come from (one stream, or a counter-based hash) are the caller's: they
// come in as callables, so the rule itself is written once. The moves and the
// no-corner-cutting rule are crowd/grid_step.h's.

#include <cmath>
#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "ai/octile.h"
#include "crowd/grid_step.h"

namespace zonesim::crowd {

/// The parameters of the step choice.
struct AntChoice {
  double alpha = 1.0;         ///< weight of the trail
  double beta = 2.0;          ///< weight of the desirability eta
  bool knows_food = true;     ///< eta = 1 / (step + octile distance to the food), else 1 / step
  double exploitation = 0.0;  ///< q0: chance of taking the strongest step outright
};

/// The step (0..7) an ant at c takes toward `food`, or -1 at a dead end (every allowed
/// neighbour walked). trail(k, n): the trail on step k, which leads to n; open(n): n not yet
/// walked this trip; uniform(i): the choice's draw i in [0, 1), taken only when needed and in
/// order (0: exploit or explore, 1: the draw in proportion to the weights).
template <typename Trail, typename Open, typename Uniform>
int chooseAntStep(const ai::GridMap& map, ai::Cell c, ai::Cell food, const AntChoice& rule,
                  Trail&& trail, Open&& open, Uniform&& uniform) {
  double weight[8];
  double total = 0, strongest = -1;
  int best = -1;
  for (int k = 0; k < 8; ++k) {
    weight[k] = 0;
    if (!gridStepAllowed(map, c, k)) continue;
    const ai::Cell n = gridStep(c, k);
    if (!open(n)) continue;
    const double tau = trail(k, n);
    const double step = k >= 4 ? ai::kDiagonalCost : 1.0;
    const double eta = rule.knows_food ? 1.0 / (step + ai::octileDistance(n, food)) : 1.0 / step;
    weight[k] = std::pow(tau, rule.alpha) * std::pow(eta, rule.beta);
    total += weight[k];
    if (weight[k] > strongest) {
      strongest = weight[k];
      best = k;
    }
  }
  if (best < 0) return -1;
  int chosen = best;
  if (uniform(0) >= rule.exploitation) {
    double pick = uniform(1) * total;
    for (int k = 0; k < 8; ++k) {
      if (weight[k] <= 0) continue;
      chosen = k;
      pick -= weight[k];
      if (pick < 0) break;
    }
  }
  return chosen;
}

/// The colony's preferred route into `out`, nest first: from the nest, always the allowed step
/// to a cell not yet on the route whose strength(c, k, n) is greatest (the first such step on
/// ties), until the food. False when it dead-ends before (out then holds the part walked).
template <typename Strength>
bool strongestTrailRoute(const ai::GridMap& map, ai::Cell nest, ai::Cell food, Strength&& strength,
                         std::vector<ai::Cell>& out) {
  std::vector<std::uint8_t> visited(std::size_t(map.width()) * std::size_t(map.height()), 0);
  out.assign(1, nest);
  visited[std::size_t(map.index(nest.x, nest.y))] = 1;
  while (!(out.back() == food)) {
    const ai::Cell c = out.back();
    int best = -1;
    decltype(strength(c, 0, c)) strongest = -1;
    for (int k = 0; k < 8; ++k) {
      if (!gridStepAllowed(map, c, k)) continue;
      const ai::Cell n = gridStep(c, k);
      if (visited[std::size_t(map.index(n.x, n.y))]) continue;
      const auto t = strength(c, k, n);
      if (t > strongest) {
        strongest = t;
        best = k;
      }
    }
    if (best < 0) return false;
    const ai::Cell n = gridStep(c, best);
    visited[std::size_t(map.index(n.x, n.y))] = 1;
    out.push_back(n);
  }
  return true;
}

}  // namespace zonesim::crowd
