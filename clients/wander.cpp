#include "clients/wander.h"

#include <algorithm>
#include <cmath>

namespace zonesim::clients {

Wander::Wander(const SceneBox& world, double retarget_seconds, std::uint64_t seed,
               std::uint64_t stream, double speed)
    : world_(world),
      retarget_seconds_(retarget_seconds),
      arrive_distance_(std::max(kArriveDistance, speed * kArriveSeconds)),
      rng_(seed, stream) {}

void Wander::retarget(double t) {
  target_x_ = rng_.uniform(world_.min.x, world_.max.x);
  target_z_ = rng_.uniform(world_.min.z, world_.max.z);
  chosen_at_ = t;
  has_target_ = true;
  ++retargets_;
}

Move Wander::step(double x, double z, double t) {
  if (!has_target_ || t - chosen_at_ >= retarget_seconds_) retarget(t);
  double dx = target_x_ - x, dz = target_z_ - z;
  double d = std::sqrt(dx * dx + dz * dz);
  if (d < arrive_distance_) {
    retarget(t);
    dx = target_x_ - x;
    dz = target_z_ - z;
    d = std::sqrt(dx * dx + dz * dz);
  }
  if (d < 1e-9) return {};
  return {float(dx / d), float(dz / d)};
}

}  // namespace zonesim::clients
