#pragma once
// The discovery service's table: who is playing, as what, at which address. Entries expire
// unless their owner registers again within its time to live, so a crashed host or peer
// leaves the list without anyone telling the service. No I/O: the service and the tests
// drive it with their own clock.

#include <cstdint>
#include <map>
#include <vector>

#include "topologies/topology_role.h"
#include "wire/udp_socket.h"

namespace zonesim::topo {

/// One registered player.
struct Registration {
  std::uint32_t player = 0;
  Role role = Role::Peer;
  gateway::Endpoint address;
};

/// Longest time to live a registration may ask for: a forgotten entry must not linger.
inline constexpr double kMaxTtlSeconds = 3600;

class DiscoveryRegistry {
 public:
  /// Adds or refreshes (same player) an entry alive until now_s + ttl_s. Throws
  /// std::invalid_argument unless 0 < ttl_s <= kMaxTtlSeconds.
  void add(const Registration& r, double now_s, double ttl_s);
  /// The entries alive at now_s, by player; expired ones are forgotten.
  std::vector<Registration> list(double now_s);
  /// Entries held, expired or not (until the next list()).
  std::size_t size() const { return entries_.size(); }

 private:
  struct Entry {
    Registration registration;
    double expires_s;
  };
  std::map<std::uint32_t, Entry> entries_;  // ordered: lists come out by player
};

}  // namespace zonesim::topo
