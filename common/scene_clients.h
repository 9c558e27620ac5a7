#pragma once
// The scene's `clients` key: defaults for the simulated players, and the kinds they come in.

#include <cstdint>
#include <optional>
#include <vector>

#include "common/player_kind.h"

namespace zonesim {

/// One kind of player a scene has (`clients.kinds`): how its avatar moves and how far it sees.
struct PlayerKind {
  PlayerKindId id = PlayerKindId::Walker;
  double speed = 5.0;  ///< m/s, the avatar's top speed
  double nimbus = 60;  ///< metres, its range of interest (grown with speed, interest.max_nimbus)
  double height = 0;   ///< metres above the ground (world.min.y) it flies at; 0: on the ground
  double share = 1;    ///< fraction of the fleet client_stub gives this kind
};

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
  /// `clients.kinds` in ascending id; empty when the scene has no such key, and then the one
  /// kind is a walker with `speed` and `nimbus` (read them through playerKinds()).
  std::vector<PlayerKind> kinds;
};

/// The scene's kinds in ascending id: `clients.kinds`, or without it the implicit walker (speed
/// and nimbus of the profile, share 1), so a scene from before kinds runs as it did.
std::vector<PlayerKind> playerKinds(const ClientProfile& clients);

/// The scene's kind with this wire id, or nothing when the scene has none of it (or the byte
/// names no kind at all).
std::optional<PlayerKind> playerKind(const ClientProfile& clients, std::uint8_t id);

}  // namespace zonesim
