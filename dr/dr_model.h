#pragma once
// The dead-reckoning model every side runs: the zone (to decide when receivers have drifted too
// far), the gateway (to judge interest) and the clients (to show remote entities). DIS family:
// static, first order (position + velocity) and second order (+ acceleration) in the world
// frame, with the orientation either fixed or rotating at a constant angular velocity. Plain
// doubles, no Eigen: the same arithmetic on every side gives the same prediction.

#include <cstdint>

#include "dr/dr_state.h"

namespace zonesim::dr {

/// How position is extrapolated.
enum class Order : std::uint8_t { Static = 0, First = 1, Second = 2 };
/// How orientation is extrapolated.
enum class Spin : std::uint8_t { Fixed = 0, Rotating = 1 };

/// The model chosen for an entity type.
struct Model {
  Order order = Order::First;
  Spin spin = Spin::Fixed;
};

/// Position after dt seconds under the model's order.
V3 predictPosition(const State& s, Order order, double dt);
/// Velocity after dt seconds (constant for first order, v + a dt for second, zero for static).
V3 predictVelocity(const State& s, Order order, double dt);
/// Orientation after dt seconds: fixed, or rotated by angvel * dt about a world axis.
Q4 predictRotation(const State& s, Spin spin, double dt);

/// Euclidean distance.
double distance(const V3& a, const V3& b);
/// The rotation angle (radians, 0..pi) taking a to b.
double angleBetween(const Q4& a, const Q4& b);
/// q scaled to unit length (identity if degenerate).
Q4 normalized(const Q4& q);

/// When the sender must send: thresholds and heartbeat.
struct Thresholds {
  double position = 0.5;          ///< metres
  double orientation_rad = 0.05;  ///< radians
  double heartbeat_s = 5.0;       ///< seconds between updates at the latest
};

/// Why an update is due (None: the receivers' prediction is still good).
/// Rest: the entity stopped (a body fell asleep) while receivers still extrapolate a motion.
enum class Due : std::uint8_t { None, Position, Orientation, Heartbeat, Rest };

/// Compares the truth now with what receivers predict from `sent` after `elapsed` seconds.
Due updateDue(const State& sent, const Model& m, double elapsed, const V3& true_pos,
              const Q4& true_rot, const Thresholds& t, double heartbeat_s);

/// This entity's heartbeat period: between 75% and 100% of the setting, fixed per id, so that
/// entities first sent together (a keyframe, a scene start) do not all beat in the same tick.
double heartbeatPeriod(std::uint64_t id, double heartbeat_s);

}  // namespace zonesim::dr
