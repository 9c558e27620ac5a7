#pragma once
// Loss, delay and reordering injected into one side's datagrams, for tests and benchmarks: the
// gateway and the clients each have one (a setting, off by default). Outgoing datagrams are
// dropped with probability `loss`, or held for delay + U(0, jitter) before they go out, so a
// jitter larger than the send interval reorders them; incoming ones are dropped with `loss`.

#include <cstdint>
#include <queue>
#include <span>
#include <vector>

#include "common/rng.h"
#include "wire/udp_socket.h"

namespace zonesim::gateway {

/// What to inject.
struct ImpairmentSettings {
  double loss = 0;       ///< probability each datagram (either direction) is dropped
  double delay_ms = 0;   ///< added to every outgoing datagram
  double jitter_ms = 0;  ///< plus uniform [0, jitter): reorders when larger than the spacing
  std::uint64_t seed = 1;
  bool active() const { return loss > 0 || delay_ms > 0 || jitter_ms > 0; }
};

/// Counts of what was injected.
struct ImpairmentCounters {
  std::uint64_t dropped_out = 0, dropped_in = 0, delayed = 0;
};

class Impairment {
 public:
  explicit Impairment(const ImpairmentSettings& s, std::uint64_t stream = 0)
      : s_(s), rng_(s.seed, stream) {}

  /// Sends now, holds, or drops an outgoing datagram; false only if the socket refused it.
  bool send(UdpSocket& socket, const Endpoint& to, std::span<const std::uint8_t> bytes,
            std::int64_t now_ns);
  /// True if an incoming datagram is to be dropped.
  bool dropIncoming();
  /// Sends held datagrams whose time has come; returns how many the socket refused.
  int flush(UdpSocket& socket, std::int64_t now_ns);
  /// When the next held datagram is due (INT64_MAX if none).
  std::int64_t nextDueNs() const;
  bool active() const { return s_.active(); }
  const ImpairmentCounters& counters() const { return counters_; }

 private:
  struct Held {
    std::int64_t due_ns;
    std::uint64_t order;  // FIFO among equal due times
    Endpoint to;
    std::vector<std::uint8_t> bytes;
    bool operator>(const Held& o) const {
      return due_ns != o.due_ns ? due_ns > o.due_ns : order > o.order;
    }
  };

  ImpairmentSettings s_;
  Pcg32 rng_;
  std::priority_queue<Held, std::vector<Held>, std::greater<>> held_;
  std::uint64_t order_ = 0;
  ImpairmentCounters counters_;
};

}  // namespace zonesim::gateway
