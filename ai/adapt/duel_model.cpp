#include "ai/adapt/duel_model.h"

#include <cmath>
#include <limits>

namespace zonesim::ai::adapt {

namespace {
// Bisection halves [0, 1] this often: 2^-30 is far below any step the guards let through.
constexpr int kBisections = 30;
}  // namespace

Basis basisAt(double h, double d) {
  const double u = 2 * h - 1, v = 2 * d - 1;  // centred: the Newton fit stays well conditioned
  return {1, u, v, u * u, u * v, v * v, u * u * u, u * u * v, u * v * v, v * v * v};
}

double DuelModel::winProbability(double h, double d) const {
  const Basis x = basisAt(h, d);
  double z = 0;
  for (std::size_t i = 0; i < kBasisSize; ++i) z += weights[i] * x[i];
  // An overflowing logit means broken weights, not certainty: say so, and the guards fall back.
  if (!std::isfinite(z)) return std::numeric_limits<double>::quiet_NaN();
  return 1 / (1 + std::exp(-z));
}

double DuelModel::difficultyFor(double h, double target) const {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  // Harder NPCs lose the player rounds: the prediction falls with d, and the root is bracketed.
  double lo = 0, hi = 1;
  const double p_lo = winProbability(h, lo), p_hi = winProbability(h, hi);
  if (!std::isfinite(p_lo) || !std::isfinite(p_hi)) return kNaN;
  if (p_lo <= target) return lo;
  if (p_hi >= target) return hi;
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double p = winProbability(h, mid);
    if (!std::isfinite(p)) return kNaN;
    (p > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace zonesim::ai::adapt
