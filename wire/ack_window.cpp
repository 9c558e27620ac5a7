#include "wire/ack_window.h"

#include <algorithm>
#include <cmath>

namespace zonesim::gateway {

bool AckWindow::receive(std::uint32_t seq) {
  if (seq == 0) return false;
  if (seq > highest_) {
    std::uint32_t shift = seq - highest_;
    // The old highest becomes bit shift - 1; anything shifted past bit 31 is forgotten.
    bits_ = shift > 32 ? 0 : shift == 32 ? 0 : (bits_ << shift);
    if (highest_ != 0 && shift <= 32) bits_ |= 1u << (shift - 1);
    highest_ = seq;
    return true;
  }
  if (seq == highest_) return false;
  std::uint32_t back = highest_ - seq;  // >= 1
  if (back > 32) return false;
  std::uint32_t bit = 1u << (back - 1);
  if (bits_ & bit) return false;
  bits_ |= bit;
  return true;
}

ResendTracker::ResendTracker(double min_rto_s, double max_rto_s)
    : flights_(kFlights), min_rto_s_(min_rto_s), max_rto_s_(max_rto_s) {}

void ResendTracker::sent(std::uint32_t seq, std::span<const std::uint64_t> ids, Carried what,
                         std::int64_t now_ns) {
  Flight& f = flights_[seq % kFlights];
  f.seq = seq;
  f.sent_ns = now_ns;
  f.what = what;
  f.acked = false;
  f.ids.assign(ids.begin(), ids.end());
  for (std::uint64_t id : ids) {
    const Pending* was = pending_.find(id);
    std::uint32_t from = what != Carried::Spawn                           ? 0
                         : was != nullptr && was->what == Carried::Spawn ? was->spawn_from
                                                                          : seq;
    pending_.insertOrAssign(id, Pending{what, seq, now_ns, from});
  }
  if (!ids.empty()) oldest_pending_ns_ = std::min(oldest_pending_ns_, now_ns);
}

void ResendTracker::onAck(std::uint32_t ack, std::uint32_t bits, std::int64_t now_ns) {
  // A forged or corrupt ack beyond what was sent acknowledges nothing.
  if (ack == 0 || ack >= next_seq_) return;
  ackOne(ack, now_ns);
  for (std::uint32_t i = 0; i < 32 && ack > i + 1; ++i)
    if (bits & (1u << i)) ackOne(ack - 1 - i, now_ns);
}

void ResendTracker::ackOne(std::uint32_t seq, std::int64_t now_ns) {
  Flight& f = flights_[seq % kFlights];
  if (f.seq != seq || f.acked) return;  // fell out of the ring, or a repeated ack
  f.acked = true;
  ++acked_;
  newest_acked_sent_ns_ = std::max(newest_acked_sent_ns_, f.sent_ns);
  // RTT sample as in TCP (RFC 6298), from the first ack of each datagram.
  rtt_.sample(double(now_ns - f.sent_ns) * 1e-9);
  // Only the datagram holding an entity's newest state (or despawn) settles it: an ack of an
  // older one says nothing about the newer state. But an ack of an older Spawn of the same run
  // says the client holds the entity: the newer state in flight is then an update. Without
  // this, an entity that changes every tick over a link whose ack takes longer than a tick
  // would go as a Spawn for ever (each tick's Spawn overtaking the last before its ack).
  for (std::uint64_t id : f.ids) {
    Pending* p = pending_.find(id);
    if (p == nullptr) continue;
    if (p->seq == seq)
      pending_.erase(id);
    else if (f.what == Carried::Spawn && p->what == Carried::Spawn && seq >= p->spawn_from)
      p->what = Carried::Update;
  }
  f.ids.clear();
}

bool ResendTracker::spawnPending(std::uint64_t id) const {
  const Pending* p = pending_.find(id);
  return p != nullptr && p->what == Carried::Spawn;
}

std::int64_t ResendTracker::rtoNs() const {
  return std::int64_t(rtt_.rtoS(min_rto_s_, max_rto_s_, max_rto_s_ * 0.25) * 1e9);
}

ResendDue ResendTracker::due(std::int64_t now_ns, LossDetection how) const {
  ResendDue d;
  due(now_ns, how, d);
  return d;
}

void ResendTracker::due(std::int64_t now_ns, LossDetection how, ResendDue& d) const {
  d.clear();
  std::int64_t rto = rtoNs();
  bool later_acks = how == LossDetection::LaterAck;
  // Nothing pending was sent long enough ago, or before the newest acknowledged datagram.
  if (now_ns - oldest_pending_ns_ < rto &&
      !(later_acks && oldest_pending_ns_ < newest_acked_sent_ns_))
    return;
  std::int64_t oldest = INT64_MAX;
  pending_.forEach([&](std::uint64_t id, const Pending& p) {
    oldest = std::min(oldest, p.sent_ns);
    bool overtaken = later_acks && p.sent_ns < newest_acked_sent_ns_;
    if (!overtaken && now_ns - p.sent_ns < rto) return;
    (p.what == Carried::Spawn    ? d.spawns
     : p.what == Carried::Update ? d.updates
                                 : d.despawns)
        .push_back(id);
  });
  oldest_pending_ns_ = oldest;
  std::sort(d.spawns.begin(), d.spawns.end());
  std::sort(d.updates.begin(), d.updates.end());
  std::sort(d.despawns.begin(), d.despawns.end());
}

}  // namespace zonesim::gateway
