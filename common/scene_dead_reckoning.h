#pragma once
// The scene's `dead_reckoning` key: when the zone sends an entity's state, with which model,
// and how finely the state is quantised on the wire.

namespace zonesim {

/// The dead-reckoning model of one entity type (DIS family, world frame).
struct DeadReckoningModel {
  /// Static: position only; First: + velocity; Second: + acceleration.
  enum class Order { Static, First, Second };
  Order order = Order::First;
  bool rotating = false;  ///< orientation extrapolated with the angular velocity, else fixed
};

/// Resolution and range of the quantised states sent to clients.
struct StateQuantisation {
  double position_resolution = 1.0 / 512;  ///< metres per step (relative to the interest cell)
  double max_speed = 64;                   ///< m/s, per axis
  double velocity_resolution = 1.0 / 128;  ///< m/s per step
  double max_acceleration = 64;            ///< m/s^2, per axis
  double acceleration_resolution = 1.0 / 32;
  double max_angular_velocity = 32;  ///< rad/s, per axis
  double angular_velocity_resolution = 1.0 / 256;
  int rotation_bits = 10;  ///< per smallest-three component
};

/// Sender-side dead reckoning: thresholds, heartbeat, and the model per entity type.
struct DeadReckoning {
  double position_threshold = 0.5;         ///< metres of prediction error before an update is sent
  double heartbeat_seconds = 5.0;          ///< an update at least this often per entity
  double orientation_threshold_deg = 3.0;  ///< degrees of orientation error before an update
  DeadReckoningModel npc;
  DeadReckoningModel avatar;
  DeadReckoningModel rigid_body{DeadReckoningModel::Order::Second, true};
  DeadReckoningModel emitter{DeadReckoningModel::Order::Static, false};
  StateQuantisation quantisation;
};

}  // namespace zonesim
