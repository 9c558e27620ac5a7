#pragma once
// Logging players in through the lobby before they play: each player's socket asks the lobby
// for a gateway (LoginRequest, retried until answered) and gets back the gateway's address and a
// connect token bound to that socket's address and port. All players log in at once, over one
// epoll loop, so a fleet of thousands is not serialised behind round trips, and each reply
// costs its own socket, not a pass over every player's.

#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "wire/udp_socket.h"
#include "wire/wire_verify.h"

namespace zonesim::clients {

/// Where the lobby sent one player.
struct LoginTicket {
  gateway::Endpoint gateway;
  std::uint16_t gateway_id = 0;
  std::uint64_t player_id = 0;
  std::vector<std::uint8_t> connect_token;
};

/// How logins are tried.
struct LobbyLoginSettings {
  gateway::Endpoint lobby;
  double retry_s = 0.5;    ///< a request unanswered (or refused with retry) this long is sent again
  double timeout_s = 10;   ///< the whole login gives up after this
  std::uint64_t seed = 1;  ///< mixed into the request nonces
};

/// What the logins counted.
struct LoginStats {
  std::uint64_t requests = 0;   ///< requests sent, retries included
  std::uint64_t refusals = 0;   ///< refusals received (retried while they said so)
  gateway::DropCounters drops;  ///< replies dropped by the checks (or not from the lobby)
};

/// Logs every socket in; returns one ticket per socket, in order. Throws std::runtime_error
/// naming the lobby, how many players got no gateway and the last refusal's reason if any is
/// not granted within timeout_s, or if the lobby refuses for good; returns early, with no
/// tickets, if stop is set.
std::vector<LoginTicket> loginAll(std::span<gateway::UdpSocket> sockets,
                                  const LobbyLoginSettings& settings, const std::atomic<bool>& stop,
                                  LoginStats* stats = nullptr);

}  // namespace zonesim::clients
