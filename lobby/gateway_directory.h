#pragma once
// The lobby's picture of the gateways, from their load reports (topic zs_gateway_load), and its
// choice of the least-loaded one. Between two reports (a second apart) many players may log in
// at once, so a gateway's load counts, beside the sessions it reported, the grants the lobby
// made that it has not yet reported as logins; a grant whose token expired unused stops
// counting. One lobby per cluster is assumed: a second lobby's logins would show up here as
// ours and make our estimate low (the reported sessions still correct it a second later).

#include <cstdint>
#include <deque>
#include <map>
#include <optional>

#include "wire/udp_socket.h"

namespace zonesim::lobby {

/// One load report of a gateway.
struct GatewayReport {
  std::uint16_t gateway_id = 0;
  std::uint16_t incarnation = 0;
  gateway::Endpoint address;
  std::uint32_t sessions = 0, max_sessions = 0;
  std::uint64_t logins = 0;
};

/// A gateway as the lobby knows it.
struct GatewayEntry {
  GatewayReport last;                   ///< the newest report
  std::int64_t heard_ns = 0;            ///< when it arrived (the lobby's steady clock)
  std::deque<std::uint64_t> in_flight;  ///< expiries of grants not yet reported as logins
  std::uint64_t granted = 0;            ///< grants the lobby made for it since start
};

/// The gateways heard of, by id, and the choice among them.
class GatewayDirectory {
 public:
  /// A gateway silent for stale_after_ns (three report periods, say) is not chosen.
  explicit GatewayDirectory(std::int64_t stale_after_ns);

  /// Takes a report: the gateway's logins since the previous one settle that many grants.
  void report(const GatewayReport& r, std::int64_t now_ns);
  /// The least-loaded live gateway with room (ties: the lowest id), or nullptr.
  const GatewayEntry* pick(std::int64_t now_ns, std::uint64_t now_unix_ms);
  /// Counts a grant for gateway id, whose token expires at expiry_unix_ms.
  void granted(std::uint16_t gateway_id, std::uint64_t expiry_unix_ms);
  /// Sessions plus grants in flight.
  static std::uint64_t load(const GatewayEntry& e);
  /// Gateways heard from within the stale limit.
  std::size_t live(std::int64_t now_ns) const;
  /// Every gateway ever heard of, by id.
  const std::map<std::uint16_t, GatewayEntry>& entries() const { return gateways_; }

 private:
  std::int64_t stale_after_ns_;
  std::map<std::uint16_t, GatewayEntry> gateways_;
};

}  // namespace zonesim::lobby
