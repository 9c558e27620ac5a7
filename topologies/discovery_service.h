#pragma once
// The discovery service: a UDP server in front of a DiscoveryRegistry. Each datagram is one
// request (topologies/discovery_message.h); each gets one reply, "error WHAT" for anything it
// cannot parse, so a node with a bad address or role is told what is wrong.

#include <atomic>
#include <cstdint>
#include <span>
#include <string>

#include "topologies/discovery_registry.h"
#include "wire/udp_socket.h"

namespace zonesim::topo {

/// Counts for the service's summary.
struct DiscoveryCounters {
  std::uint64_t registers = 0, lists = 0, errors = 0;
};

class DiscoveryService {
 public:
  /// Binds local; throws gateway::BindError when it cannot.
  explicit DiscoveryService(const gateway::Endpoint& local) : socket_(local) {}
  const gateway::Endpoint& local() const { return socket_.local(); }
  /// Answers requests until stop is set or duration_s passed (0: no limit).
  void run(const std::atomic<bool>& stop, double duration_s);
  /// The reply to one request arriving at now_s (no I/O; the tests call it directly).
  std::string answer(std::span<const std::uint8_t> request, double now_s);
  const DiscoveryCounters& counters() const { return counters_; }

 private:
  gateway::UdpSocket socket_;
  DiscoveryRegistry registry_;
  DiscoveryCounters counters_;
};

}  // namespace zonesim::topo
