#pragma once
// The discovery service's datagrams: one line of ASCII text each, since they are rare (a
// register every few seconds per player, a list until the game starts) and a person can
// read them in a capture.
//
//   register PLAYER ROLE A.B.C.D:PORT TTL_S   ->  ok
//   list                                      ->  peers N, then N lines PLAYER ROLE A.B.C.D:PORT
//   anything wrong                            ->  error WHAT
//
// Parsing throws std::invalid_argument whose message names the field that is wrong.

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "topologies/discovery_registry.h"

namespace zonesim::topo {

/// Longest request or reply: one datagram, well inside an Ethernet MTU.
inline constexpr std::size_t kMaxDiscoveryBytes = 1400;

/// "register": add or refresh this player's entry.
struct RegisterRequest {
  Registration registration;
  double ttl_s = 0;
};
/// "list": the entries alive now.
struct ListRequest {};

using DiscoveryRequest = std::variant<RegisterRequest, ListRequest>;

/// The request in text; throws std::invalid_argument naming what is wrong.
DiscoveryRequest parseRequest(std::string_view text);
std::string formatRequest(const DiscoveryRequest& request);

/// The reply to a list.
std::string formatPeers(const std::vector<Registration>& entries);
/// The entries of a "peers" reply; throws std::invalid_argument on an "error" reply (its
/// message) or anything malformed.
std::vector<Registration> parsePeers(std::string_view text);

/// A dotted IPv4 "A.B.C.D:PORT" with PORT 1-65535 (no names: the service resolves nothing).
gateway::Endpoint parseDottedEndpoint(std::string_view text);

}  // namespace zonesim::topo
