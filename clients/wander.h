#pragma once
// The wander profile: walk toward a random point anywhere in the world, choose a new one on
// arrival or after retarget_seconds. Targets span the whole world, so players cross zone borders
// and exercise handoff. Each player draws from its own Pcg32, so runs repeat for a seed. How
// near counts as arrived grows with the player's speed (its kind's): a flyer passes a target
// too fast to come within a walker's two metres of it.

#include <cstdint>

#include "common/rng.h"
#include "common/scene_geometry.h"

namespace zonesim::clients {

/// A planar move request, length <= 1.
struct Move {
  float x = 0, z = 0;
};

class Wander {
 public:
  /// seed and stream (e.g. the player index) select the player's generator; speed (m/s) is the
  /// avatar's top speed.
  Wander(const SceneBox& world, double retarget_seconds, std::uint64_t seed, std::uint64_t stream,
         double speed = 5.0);

  /// The move toward the current target from (x, z) at time t (seconds), retargeting if due.
  Move step(double x, double z, double t);
  double targetX() const { return target_x_; }
  double targetZ() const { return target_z_; }
  std::uint64_t retargets() const { return retargets_; }
  /// Within this distance (metres) a target counts as reached.
  double arriveDistance() const { return arrive_distance_; }

  /// The least arrival distance (metres), a walker's.
  static constexpr double kArriveDistance = 2.0;
  /// A target counts as reached within the distance the avatar covers in this time at its top
  /// speed (at least kArriveDistance): inputs steer it every 50 ms and its acceleration turns
  /// a flyer's heading in about a second, so it passes a target rather than stopping on it.
  static constexpr double kArriveSeconds = 0.25;

 private:
  void retarget(double t);

  SceneBox world_;
  double retarget_seconds_;
  double arrive_distance_;
  Pcg32 rng_;
  double target_x_ = 0, target_z_ = 0;
  double chosen_at_ = 0;
  bool has_target_ = false;
  std::uint64_t retargets_ = 0;
};

}  // namespace zonesim::clients
