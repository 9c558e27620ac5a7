#pragma once
// A soft constraint's spring for one sub-step (Box2D v3's form): contacts and joints of the
// soft step both use it, each with its own frequency.

#include <cmath>
#include <numbers>

namespace zonesim::physics {

/// A soft constraint's spring as bias rate and scales for one sub-step.
struct Softness {
  double bias_rate = 0.0;      ///< 1/s applied to the position error.
  double mass_scale = 1.0;     ///< Scales the effective mass.
  double impulse_scale = 0.0;  ///< Fraction of the accumulated impulse relaxed each pass.
};

/// Softness of a spring of `hertz` and `damping_ratio` integrated implicitly over h (a rigid
/// constraint, no bias, when hertz is not positive).
inline Softness makeSoftness(double hertz, double damping_ratio, double h) {
  if (hertz <= 0.0) return Softness{};
  const double omega = 2.0 * std::numbers::pi * hertz;
  const double a1 = 2.0 * damping_ratio + h * omega;
  const double a2 = h * omega * a1;
  const double a3 = 1.0 / (1.0 + a2);
  return Softness{omega / a1, a2 * a3, a3};
}

}  // namespace zonesim::physics
