#pragma once
// The plain state a dead-reckoning receiver holds of an entity (dr/dr_model.h extrapolates it).
// Apart from the model so that stores of sent states (zone_node/net/dead_reckoning_state.h)
// need not see the model's functions.

namespace zonesim::dr {

/// A plain 3-vector.
struct V3 {
  double x = 0, y = 0, z = 0;
};

/// A unit quaternion (x, y, z, w).
struct Q4 {
  double x = 0, y = 0, z = 0, w = 1;
};

/// What a receiver was last told of an entity, valid at the time it was sampled.
struct State {
  V3 pos, vel, acc;
  Q4 rot;
  V3 angvel;  ///< world frame, rad/s
};

}  // namespace zonesim::dr
