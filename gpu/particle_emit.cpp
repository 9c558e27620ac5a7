#include "gpu/particle_emit.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "gpu/particle_ledger.h"

namespace zonesim::gpu {
namespace {

bool finite(const Vec3d& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void require(bool ok, const char* field, const std::string& rule) {
  if (!ok) throw std::invalid_argument(std::string("EmitSpec.") + field + " " + rule);
}

}  // namespace

EmitSampler::EmitSampler(const EmitSpec& spec) {
  require(finite(spec.origin), "origin", "must be finite");
  require(spec.origin.y >= 0.0, "origin", "must be on or above the ground (y >= 0)");
  require(finite(spec.direction), "direction", "must be finite");
  double length =
      std::sqrt(spec.direction.x * spec.direction.x + spec.direction.y * spec.direction.y +
                spec.direction.z * spec.direction.z);
  require(length > 0.0, "direction", "must not be zero");
  require(spec.cone_half_angle >= 0.0 && spec.cone_half_angle <= std::numbers::pi,
          "cone_half_angle", "must be in [0, pi]");
  require(std::isfinite(spec.speed) && spec.speed >= 0.0, "speed", "must be finite and >= 0");
  life_us_ = toMicros(spec.lifetime, "EmitSpec.lifetime");

  axis_ = {spec.direction.x / length, spec.direction.y / length, spec.direction.z / length};
  // Branchless orthonormal basis around the axis (Duff et al., JCGT 2017).
  double sign = std::copysign(1.0, axis_.z);
  double a = -1.0 / (sign + axis_.z);
  double b = axis_.x * axis_.y * a;
  u_ = {1.0 + sign * axis_.x * axis_.x * a, sign * b, -sign * axis_.x};
  w_ = {b, sign + axis_.y * axis_.y * a, -axis_.y};
  cos_max_ = std::cos(spec.cone_half_angle);
  speed_ = spec.speed;
}

Vec3d EmitSampler::velocity(Pcg32& rng) const {
  // cos(theta) uniform in [cos_max, 1] is uniform in solid angle over the cap.
  double cos_theta = 1.0 - rng.uniform() * (1.0 - cos_max_);
  double phi = 2.0 * std::numbers::pi * rng.uniform();
  double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  double c = std::cos(phi) * sin_theta;
  double s = std::sin(phi) * sin_theta;
  return {speed_ * (axis_.x * cos_theta + u_.x * c + w_.x * s),
          speed_ * (axis_.y * cos_theta + u_.y * c + w_.y * s),
          speed_ * (axis_.z * cos_theta + u_.z * c + w_.z * s)};
}

}  // namespace zonesim::gpu
