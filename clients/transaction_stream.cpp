#include "clients/transaction_stream.h"

#include <algorithm>
#include <cmath>

namespace zonesim::clients {

namespace {
// ledger::Kind and ledger::TxStatus values (the client does not link the ledger).
constexpr std::uint8_t kLoot = 2, kPurchase = 3, kScore = 4;
constexpr std::uint8_t kCommitted = 0, kAlreadyCommitted = 1, kConflict = 2;
}  // namespace

TransactionStream::TransactionStream(double rate_per_s, std::uint64_t seed, std::int64_t start_ns)
    : period_ns_(rate_per_s > 0 ? std::int64_t(std::llround(1e9 / rate_per_s)) : 0),
      rng_(seed, 0x7a11),
      sender_() {
  // A random phase, so a fleet's transactions do not all come in the same millisecond.
  next_make_ns_ = start_ns + (period_ns_ > 0 ? std::int64_t(rng_.uniform() * double(period_ns_)) : 0);
}

gateway::TransactionInfo TransactionStream::make(std::uint32_t seq) {
  gateway::TransactionInfo t;
  t.seq = seq;
  std::uint32_t pick = rng_.next() % 10;
  if (pick < 5) {  // loot: a few of one of 1,000 items
    t.kind = kLoot;
    t.item = 1 + rng_.next() % 1000;
    t.amount = 1 + std::int64_t(rng_.next() % 5);
  } else if (pick < 8) {  // a purchase at a price
    t.kind = kPurchase;
    t.item = 1 + rng_.next() % 1000;
    t.amount = 1;
    t.price = 10 + std::int64_t(rng_.next() % 91);
  } else {  // a score for the leaderboard
    t.kind = kScore;
    t.score = std::int64_t(rng_.next() % 100000);
  }
  return t;
}

std::int64_t TransactionStream::due(
    std::int64_t now_ns, const std::function<void(const gateway::TransactionInfo&)>& send) {
  if (!active()) return INT64_MAX;
  while (now_ns >= next_make_ns_) {
    next_make_ns_ += period_ns_;
    if (next_make_ns_ <= now_ns - 10 * period_ns_) next_make_ns_ = now_ns;  // a stalled fleet
    std::optional<std::uint32_t> seq = sender_.push({});
    if (!seq) {
      ++counters_.refused_window_full;
      continue;
    }
    pending_.emplace(*seq, make(*seq));
    ++counters_.made;
  }
  sender_.sendDue(now_ns, [&](std::uint32_t seq, std::span<const std::uint8_t>) {
    auto p = pending_.find(seq);
    if (p == pending_.end()) return;  // decided above a gap: no need to send it again
    if (first_sent_ns_.try_emplace(seq, now_ns).second) {
      ++counters_.sent;
      // With everything before it decided, the zone hands it to the ledger on arrival: its
      // outcome times the round trip. Else it may wait there for a gap to fill.
      if (decided_ + 1 == seq) timed_.insert(seq);
    } else {
      ++counters_.resent;
    }
    p->second.decided = decided_;
    send(p->second);
  });
  return std::min(next_make_ns_, sender_.nextDueNs() == INT64_MIN ? now_ns : sender_.nextDueNs());
}

void TransactionStream::onOutcome(std::uint32_t seq, std::uint8_t status, std::int64_t now_ns) {
  auto p = pending_.find(seq);
  if (p == pending_.end()) {
    if (seq > sender_.lastPushed() || seq == 0) {
      ++counters_.outcome_unknown;
      return;
    }
    ++counters_.outcome_repeats;
    // A repeat is the zone's duplicate ack (later ones reached it, the oldest undecided did
    // not), or the answer to a copy sent again too soon: resending the oldest then costs at
    // most one datagram a round trip.
    if (!pending_.empty()) sender_.expedite(pending_.begin()->first, now_ns);
    return;
  }
  pending_.erase(p);
  if (status == kCommitted || status == kAlreadyCommitted) {
    ++counters_.committed;
    if (status == kAlreadyCommitted) ++counters_.already_committed;
  } else if (status == kConflict) {
    ++counters_.conflicts;
  } else {
    ++counters_.failed;
  }
  auto sent = first_sent_ns_.find(seq);
  if (sent != first_sent_ns_.end()) {
    counters_.latency_ms.add(double(now_ns - sent->second) * 1e-6);
    first_sent_ns_.erase(sent);
  }
  // The ledger decides in sequence order per zone, but outcomes travel on a lossy link.
  decided_early_.insert(seq);
  while (decided_early_.erase(decided_ + 1) == 1) ++decided_;
  sender_.acknowledge(decided_, now_ns, timed_.erase(seq) == 1 ? seq : 0);
  // Undecided ones before it were probably lost on the way (the zone decides in order): again
  // now, not at their timeout.
  for (auto it = pending_.begin(); it != pending_.end() && it->first < seq; ++it)
    sender_.expedite(it->first, now_ns);
}

void TransactionStream::restart(std::int64_t now_ns) {
  counters_.failed += pending_.size();
  pending_.clear();
  first_sent_ns_.clear();
  timed_.clear();
  decided_early_.clear();
  decided_ = 0;
  sender_ = gateway::ReliableSender();
  next_make_ns_ = std::max(next_make_ns_, now_ns);
}

}  // namespace zonesim::clients
