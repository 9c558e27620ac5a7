#pragma once
// What the publish phase last told subscribers about an entity: the state receivers
// extrapolate and the window the sender estimates motion from (zone_node/net/dead_reckoning.h
// runs the model on it). A header of its own because the entity store keeps one per entity:
// it needs only the plain state (dr/dr_state.h), not the dead-reckoning model.

#include <array>

#include "common/math.h"
#include "dr/dr_state.h"

namespace zonesim::zone {

/// What the publish phase last told subscribers about the entity (sender-side dead reckoning).
struct DeadReckoningState {
  int cell = -1;    ///< interest cell it was last published in; -1 = never published here
  dr::State sent;   ///< the quantised state receivers hold
  double time = 0;  ///< sim time `sent` was sampled
  /// Velocities of the last ticks (oldest first once full): the acceleration estimate's window.
  static constexpr int kVelocityWindow = 6;
  std::array<Vec3, kVelocityWindow> vel_history{};
  int vel_count = 0;                 ///< how many of vel_history hold a tick (up to the window)
  int vel_next = 0;                  ///< where the next tick's velocity goes
  Quat last_rot = Quat::Identity();  ///< previous tick's orientation (angular velocity estimate)
  bool has_last = false;
};

}  // namespace zonesim::zone
