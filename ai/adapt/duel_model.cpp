#include "ai/adapt/duel_model.h"

#include <cmath>
#include <limits>

namespace zonesim::ai::adapt {

namespace {
// Bisection halves [0, 1] this often: 2^-20 is far below any step the guards let through.
constexpr int kBisections = 20;
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
  // For a given h the logit is a cubic in v = 2d - 1: its coefficients once, then each
  // bisection step is three multiply-adds against the target's logit (no exp).
  const double u = 2 * h - 1;
  const Basis& w = weights;
  const double c0 = w[0] + u * (w[1] + u * (w[3] + u * w[6]));
  const double c1 = w[2] + u * (w[4] + u * w[7]);
  const double c2 = w[5] + u * w[8];
  const double c3 = w[9];
  auto logit = [&](double d) {
    const double v = 2 * d - 1;
    return c0 + v * (c1 + v * (c2 + v * c3));
  };
  const double goal = std::log(target / (1 - target));
  // Harder NPCs lose the player rounds: the logit falls with d, and the root is bracketed.
  double lo = 0, hi = 1;
  const double z_lo = logit(lo), z_hi = logit(hi);
  if (!std::isfinite(z_lo) || !std::isfinite(z_hi) || !std::isfinite(goal)) return kNaN;
  if (z_lo <= goal) return lo;
  if (z_hi >= goal) return hi;
  for (int i = 0; i < kBisections; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double z = logit(mid);
    if (!std::isfinite(z)) return kNaN;
    (z > goal ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace zonesim::ai::adapt
