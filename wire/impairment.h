#pragma once
// Link impairment on one side's socket (wire/link_model.h decides each datagram's fate): the
// gateway and the clients each have one, off by default. Outgoing datagrams go through a link
// model per destination (each client's access link has its own queue and loss state) and wait
// in one time-ordered release queue; incoming ones go through one model and wait in another,
// until deliver() hands them on. netem is not available here, hence this in user space.

#include <cstdint>
#include <memory>
#include <queue>
#include <span>
#include <unordered_map>
#include <vector>

#include "wire/link_model.h"
#include "wire/udp_socket.h"

namespace zonesim::gateway {

/// What to impose, each direction.
struct ImpairmentSettings {
  LinkProfile out;  ///< outgoing datagrams (a client's uplink; the gateway's downlinks)
  LinkProfile in;   ///< incoming datagrams (a client's downlink)
  std::uint64_t seed = 1;
  bool active() const { return out.active() || in.active(); }
};

/// The --inject-loss/-delay-ms/-jitter-ms options as profiles: loss both ways, the delay and a
/// uniform jitter that may reorder on outgoing datagrams only.
ImpairmentSettings injectedImpairment(double loss, double delay_ms, double jitter_ms);

/// What each direction's models did.
struct ImpairmentCounters {
  LinkCounters out, in;
};

class Impairment {
 public:
  /// stream keeps two holders with one seed apart. Throws std::invalid_argument on a profile
  /// out of range.
  Impairment(const ImpairmentSettings& s, std::uint64_t stream = 0);

  /// Sends now, holds, or drops an outgoing datagram; false only if the socket refused it.
  bool send(UdpSocket& socket, const Endpoint& to, std::span<const std::uint8_t> bytes,
            std::int64_t now_ns);
  /// Sends held datagrams whose time has come; returns how many the socket refused.
  int flush(UdpSocket& socket, std::int64_t now_ns);

  /// Offers a received datagram to the incoming link: lost, or held until deliver().
  void receive(std::span<const std::uint8_t> bytes, const Endpoint& from, std::int64_t now_ns);
  /// Hands every held incoming datagram whose time has come to handle(bytes, from), in order.
  template <typename Handle>
  void deliver(std::int64_t now_ns, Handle&& handle) {
    while (!inbound_.empty() && inbound_.top().due_ns <= now_ns) {
      Held h = inbound_.top();
      inbound_.pop();
      handle(std::span<const std::uint8_t>(h.bytes), h.peer);
    }
  }
  /// For a receiver that handles datagrams at once (the gateway): whether the incoming link
  /// loses this one. Only for an incoming profile that loses and does nothing else.
  bool dropIncoming();

  /// When the next held datagram, either way, is due (INT64_MAX if none).
  std::int64_t nextDueNs() const;
  /// When the next held outgoing datagram is due (INT64_MAX if none).
  std::int64_t nextOutgoingDueNs() const;
  bool active() const { return active_; }
  const ImpairmentSettings& settings() const { return s_; }
  /// Sums over every destination's link.
  ImpairmentCounters counters() const;

 private:
  struct Held {
    std::int64_t due_ns;
    std::uint64_t order;  // FIFO among equal due times
    Endpoint peer;
    std::vector<std::uint8_t> bytes;
    bool operator>(const Held& o) const {
      return due_ns != o.due_ns ? due_ns > o.due_ns : order > o.order;
    }
  };
  using HeldQueue = std::priority_queue<Held, std::vector<Held>, std::greater<>>;

  LinkModel& outLink(const Endpoint& to);
  void hold(HeldQueue& q, const Fate& fate, const Endpoint& peer,
            std::span<const std::uint8_t> bytes);

  ImpairmentSettings s_;
  // Asked on every send, receive and act of every player; the profile's own test works out
  // the mean loss each time (5% of a 2,000-player fleet's CPU).
  bool active_;
  std::uint64_t stream_;
  // One per destination, created on first use (only while impairment is on, in tests and
  // benchmarks): each client's access link has its own queue and loss state.
  std::unordered_map<Endpoint, LinkModel, EndpointHash> out_links_;
  LinkModel in_link_;
  HeldQueue outbound_, inbound_;
  std::uint64_t order_ = 0;
};

}  // namespace zonesim::gateway
