#pragma once
// Reliability bookkeeping for the gateway -> client stream. Every StateBatch, Spawn and Despawn
// datagram of a session carries a sequence number; the client acknowledges them piggybacked on
// its Input and Ping datagrams (the highest seq received plus a bitfield of the 32 before it).
// The client side (AckWindow) also drops duplicates; the gateway side (ResendTracker) keeps, per
// entity, what was last sent and in which datagram, and says what to send again when that
// datagram is not acknowledged within the retransmission timeout. Resends always carry the
// entity's newest state, never the lost bytes: a stale state is worth nothing.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/flat_id_map.h"
#include "wire/rtt_estimator.h"

namespace zonesim::gateway {

/// Receiver side: which sequence numbers arrived, as the (ack, bits) pair to send back.
class AckWindow {
 public:
  /// Records seq; false if it is a duplicate or too old to tell (more than 32 below the highest).
  bool receive(std::uint32_t seq);
  /// The highest seq received (0: none yet).
  std::uint32_t ack() const { return highest_; }
  /// Bit i set: seq ack() - 1 - i was received.
  std::uint32_t bits() const { return bits_; }

 private:
  std::uint32_t highest_ = 0;
  std::uint32_t bits_ = 0;
};

/// What an entity's last datagram carried.
enum class Carried : std::uint8_t { Spawn, Update, Despawn };

/// Entities whose carrying datagram went unacknowledged past the timeout, ascending ids.
struct ResendDue {
  std::vector<std::uint64_t> spawns, updates, despawns;
  bool empty() const { return spawns.empty() && updates.empty() && despawns.empty(); }
  /// Empties the lists, keeping their storage.
  void clear() {
    spawns.clear();
    updates.clear();
    despawns.clear();
  }
};

/// How the sender recognises a lost datagram.
enum class LossDetection : std::uint8_t {
  Timeout,   ///< only when it is not acknowledged within the retransmission timeout
  LaterAck,  ///< also as soon as a datagram sent in a later tick is acknowledged before it
};

/// Sender side, one per session.
class ResendTracker {
 public:
  /// Bounds of the retransmission timeout (seconds); it follows the measured ack round trip.
  ResendTracker(double min_rto_s = 0.05, double max_rto_s = 1.0);

  /// The seq for the next datagram (from 1).
  std::uint32_t nextSeq() { return next_seq_++; }
  /// The seq nextSeq() will return.
  std::uint32_t upcoming() const { return next_seq_; }
  /// Datagram seq carried `ids` as `what` at now_ns.
  void sent(std::uint32_t seq, std::span<const std::uint64_t> ids, Carried what,
            std::int64_t now_ns);
  /// An ack (highest seq, bitfield) arrived at now_ns.
  void onAck(std::uint32_t ack, std::uint32_t bits, std::int64_t now_ns);
  /// Whether datagram seq was acknowledged (false too once it fell out of the ring of flights:
  /// a resend then is needless at worst).
  bool acknowledged(std::uint32_t seq) const {
    const Flight& f = flights_[seq % kFlights];
    return f.seq == seq && f.acked;
  }
  /// Whether the entity's spawn is not yet acknowledged (its states must go as Spawn).
  bool spawnPending(std::uint64_t id) const;
  /// Entities to send again now: their newest state (or despawn) is not acknowledged and went
  /// out over rto() ago or (LaterAck) before a datagram that is acknowledged.
  ResendDue due(std::int64_t now_ns, LossDetection how = LossDetection::Timeout) const;
  /// The same into `out` (cleared first), reusing its storage.
  void due(std::int64_t now_ns, LossDetection how, ResendDue& out) const;
  /// The retransmission timeout now, nanoseconds: smoothed ack RTT + 4 deviations, bounded.
  std::int64_t rtoNs() const;
  /// Entities with something unacknowledged.
  std::size_t pending() const { return pending_.size(); }
  /// Datagrams acknowledged so far.
  std::uint64_t acked() const { return acked_; }

 private:
  struct Pending {
    Carried what;
    std::uint32_t seq;
    std::int64_t sent_ns;
    // While `what` is Spawn: the first datagram of this run of Spawns (since the entity was
    // last sent any other way). An ack of any of them means the client holds the entity.
    std::uint32_t spawn_from = 0;
  };
  struct Flight {
    std::uint32_t seq = 0;  // 0: slot empty
    std::int64_t sent_ns = 0;
    Carried what = Carried::Update;
    bool acked = false;
    std::vector<std::uint64_t> ids;
  };
  void ackOne(std::uint32_t seq, std::int64_t now_ns);

  // Datagrams in flight by seq % size; older ones fall out, and their entities are resent on
  // timeout anyway (the timeout is per entity, not per datagram).
  static constexpr std::size_t kFlights = 1024;
  std::vector<Flight> flights_;
  FlatIdMap<Pending> pending_;  // entity id (never 0) -> what of it is unacknowledged
  // No pending entry was sent before this (a lower bound: acks only raise the true one), so
  // due() skips its scan while nothing can have timed out or been overtaken.
  mutable std::int64_t oldest_pending_ns_ = INT64_MAX;
  std::uint32_t next_seq_ = 1;
  RttEstimator rtt_;
  double min_rto_s_, max_rto_s_;
  std::uint64_t acked_ = 0;
  // Send time of the newest datagram acknowledged: anything unacknowledged sent in an earlier
  // tick was overtaken, so lost (datagrams of one tick share a send time and may be reordered).
  std::int64_t newest_acked_sent_ns_ = INT64_MIN;
};

}  // namespace zonesim::gateway
