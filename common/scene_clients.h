#pragma once
// The scene's `clients` key: defaults for the simulated players.

namespace zonesim {

/// Defaults for simulated players attached by client_stub.
struct ClientProfile {
  int players = 32;
  double speed = 5.0;           ///< m/s avatar walking speed
  double input_hz = 20;         ///< inputs per second per player
  double nimbus = 60;           ///< range of interest, metres
  double retarget_seconds = 8;  ///< how long a player walks toward one target before choosing anew
  /// The gateway's downlink budget per player, kbit/s of UDP payload; 0 = none.
  double downlink_kbps = 0;
  /// Under a budget, the error a player is shown is held as this angle from its viewpoint.
  double downlink_error_angle_deg = 0.5;
};

}  // namespace zonesim
