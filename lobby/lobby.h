#pragma once
// The lobby process: a UDP server where players log in, and a DDS reader of the gateways'
// load. One loop sleeps in poll() on the socket, waking at least every 100 ms to take new load
// reports, so a gateway is known within a tenth of a second of its report.

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include "auth/auth_key.h"
#include "lobby/gateway_directory.h"
#include "lobby/load_listener.h"
#include "lobby/login_service.h"
#include "wire/udp_socket.h"

namespace zonesim::lobby {

/// Everything a lobby is configured with.
struct LobbyConfig {
  gateway::Endpoint bind = gateway::Endpoint::loopback(0);  ///< UDP address for players
  int dds_domain = 0;                                       ///< where the gateways report
  LoginSettings login;       ///< token lifetime, player id incarnation, gateways to wait for
  double stale_after_s = 3;  ///< a gateway silent this long gets no more players
};

/// The lobby's socket, login service, directory and load reader, and its loop.
class Lobby {
 public:
  /// Binds the socket and joins the DDS domain; throws on failure.
  Lobby(const LobbyConfig& config, auth::AuthKey key);

  /// The bound address and port.
  const gateway::Endpoint& local() const { return socket_.local(); }
  /// Runs until stop is true or duration_s (if > 0) has passed.
  void run(const std::atomic<bool>& stop, double duration_s = 0);
  /// Counters, drops and what each gateway was granted, as one JSON object.
  std::string summaryJson() const;
  /// The login service (its counters), for tests and the summary.
  const LoginService& service() const { return service_; }
  /// What the lobby knows of the gateways.
  const GatewayDirectory& directory() const { return directory_; }

 private:
  void receiveAll(std::int64_t now_ns);

  gateway::UdpSocket socket_;
  GatewayDirectory directory_;
  LoginService service_;
  LoadListener listener_;
  std::vector<std::uint8_t> rx_buffer_;
  std::uint64_t send_failures_ = 0;  // replies the kernel had no room for
};

}  // namespace zonesim::lobby
