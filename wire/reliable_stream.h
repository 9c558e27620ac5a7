#pragma once
// A reliable, ordered stream of messages over a link that loses, repeats and reorders them
// (seed 3.1, "TCP for transactions"): the sender numbers each message 1, 2, ... and sends it
// again until the receiver's cumulative acknowledgement covers it; the receiver hands each
// message to its consumer exactly once, in order, holding early ones until the gap before them
// fills. The transport is the caller's: the same two ends carry a player's transactions on UDP
// (client <-> gateway) and on DDS (gateway <-> zone), where a writer's reliability does not
// survive a crashed or replaced peer.
//
// The retransmission timeout follows RFC 6298: SRTT and RTTVAR from round trips of messages
// sent once (Karn: a resent message's ack cannot say which copy it answers), timed by the
// message each ack echoes, as TCP's timestamps do; RTO = SRTT + 4 RTTVAR within [min_rto,
// max_rto], doubled when the oldest message times out, until new data is acknowledged. A
// receiver that answers messages one by one (a zone's transaction outcomes) lets the sender
// resend a gap at once (expedite) instead of at its timeout.
//
// A receiver's state is one number, the last sequence delivered: a zone keeps it in its
// checkpoint, and a restored receiver asks for everything after it again.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "wire/rtt_estimator.h"

namespace zonesim::gateway {

struct ReliableSenderOptions {
  std::size_t window = 64;        ///< messages sent and not yet acknowledged, at most
  std::int64_t initial_rto_ns = 250'000'000;
  std::int64_t min_rto_ns = 50'000'000;
  std::int64_t max_rto_ns = 2'000'000'000;
};

class ReliableSender {
 public:
  explicit ReliableSender(const ReliableSenderOptions& options = {});

  /// Queues a message: its sequence number, or nullopt when the window is full (the caller
  /// holds it, or refuses it with a reason its player is told).
  std::optional<std::uint32_t> push(std::vector<std::uint8_t> payload);
  /// Calls send(seq, payload) for each message due at now_ns: never sent, or unacknowledged
  /// for the retransmission timeout. Returns how many were sent.
  std::size_t sendDue(std::int64_t now_ns,
                      const std::function<void(std::uint32_t, std::span<const std::uint8_t>)>& send);
  /// The receiver has delivered every message up to and including `cumulative`; echo: the
  /// message whose arrival this acknowledgement answers (0: none), timed for the round trip.
  void acknowledge(std::uint32_t cumulative, std::int64_t now_ns, std::uint32_t echo = 0);
  /// The receiver has answered messages after seq but not seq: it was probably lost, so it
  /// goes at the next sendDue rather than at its timeout (as TCP's fast retransmit on
  /// selective acks), unless its last copy went out less than a round trip ago.
  void expedite(std::uint32_t seq, std::int64_t now_ns);
  /// The peer was replaced (a restarted zone, a new gateway session): every unacknowledged
  /// message goes again at the next sendDue.
  void resendAll();

  std::size_t inFlight() const { return unacked_.size(); }
  std::uint32_t lastPushed() const { return next_seq_ - 1; }
  std::uint32_t acknowledged() const { return acked_; }
  std::int64_t rtoNs() const { return rto_ns_; }
  std::uint64_t retransmissions() const { return retransmissions_; }
  /// When sendDue next has something to send (INT64_MIN: now; INT64_MAX: nothing in flight).
  std::int64_t nextDueNs() const;

 private:
  struct Pending {
    std::uint32_t seq;
    std::vector<std::uint8_t> payload;
    std::int64_t first_sent_ns = -1;  // -1: not sent yet
    std::int64_t last_sent_ns = -1;
    bool resent = false;
  };
  ReliableSenderOptions options_;
  std::deque<Pending> unacked_;  // ascending seq
  std::uint32_t next_seq_ = 1, acked_ = 0;
  std::int64_t rto_ns_;
  RttEstimator rtt_;
  std::uint64_t retransmissions_ = 0;
};

/// What became of one received message.
enum class Arrival : std::uint8_t {
  Delivered,  ///< in order: handed over, with any held ones it unblocked
  Held,       ///< early: kept until the gap before it fills
  Duplicate,  ///< delivered before, or held already
  TooFar,     ///< beyond the window past the last delivered: dropped (the sender resends)
};

class ReliableReceiver {
 public:
  /// delivered: the last sequence already delivered (0 for a new stream, a checkpoint's value
  /// after a restart); window: how far past it a message is held.
  explicit ReliableReceiver(std::uint32_t delivered = 0, std::size_t window = 64);

  /// Hands the message, and any held ones it unblocks, to deliver(seq, payload) in order.
  Arrival receive(std::uint32_t seq, std::span<const std::uint8_t> payload,
                   const std::function<void(std::uint32_t, std::span<const std::uint8_t>)>& deliver);
  /// The cumulative acknowledgement to send back: every message up to it was delivered.
  std::uint32_t delivered() const { return delivered_; }
  std::size_t held() const { return held_.size(); }
  std::uint64_t duplicates() const { return duplicates_; }

 private:
  std::uint32_t delivered_;
  std::size_t window_;
  std::map<std::uint32_t, std::vector<std::uint8_t>> held_;
  std::uint64_t duplicates_ = 0;
};

}  // namespace zonesim::gateway
