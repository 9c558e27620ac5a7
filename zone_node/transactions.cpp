#include "zone_node/transactions.h"

#include <algorithm>

#include "zone_node/net/gateway_link.h"
#include "zone_node/players.h"

namespace zonesim::zone {

namespace {

ledger::Transaction toLedger(const PlayerTransactionMsg& m, std::uint64_t tick) {
  ledger::Transaction tx;
  tx.player = m.player_id;
  tx.seq = m.seq;
  tx.kind = ledger::Kind(m.kind);  // checked by invalidReason at submit
  tx.item = m.item;
  tx.amount = m.amount;
  tx.counterparty = m.counterparty;
  tx.price = m.price;
  tx.score = m.score;
  tx.tick = tick;
  return tx;
}

}  // namespace

Transactions::Transactions(std::unique_ptr<ledger::LedgerCommitter> committer)
    : committer_(std::move(committer)) {}

Transactions::~Transactions() = default;

ledger::CommitterStats Transactions::ledgerStats() const {
  return committer_ ? committer_->stats() : ledger::CommitterStats{};
}

void Transactions::input(PlayerZone& zone) {
  if (zone.link == nullptr) return;
  for (const PlayerTransactionMsg& m : zone.link->takeTransactions()) take(zone, m);
  // Those a full committer turned away last tick.
  for (auto it = held_.begin(); it != held_.end();) {
    std::uint64_t player = it->first;
    ++it;  // release() may erase the entry
    release(zone, player);
  }
}

void Transactions::take(PlayerZone& zone, const PlayerTransactionMsg& m) {
  ++counters_.received;
  std::optional<std::size_t> i = zone.store.avatarOf(m.player_id);
  if (!i) {
    ++counters_.not_here;
    held_.erase(m.player_id);  // the avatar left: its next owner holds its own
    return;
  }
  AvatarData& a = zone.store.avatar[*i];
  if (m.decided > a.last_transaction_seq) {
    // The client has the outcome of everything up to m.decided, so each of those was decided
    // somewhere: by this zone before a restart from an older checkpoint, or by the avatar's
    // owner before a handoff. Waiting for them would wait for ever: none is sent again.
    a.last_transaction_seq = m.decided;
    ++counters_.fast_forwards;
  }
  if (m.seq <= a.last_transaction_seq) {
    // A repeat: its outcome did not reach the client, or is still to come.
    auto f = in_flight_.find(m.player_id);
    if (f != in_flight_.end() && f->second.contains(m.seq)) return;
    auto r = remembered_.find(m.player_id);
    if (r != remembered_.end()) {
      auto o = std::find_if(r->second.begin(), r->second.end(),
                            [&](const Outcome& x) { return x.seq == m.seq; });
      if (o != r->second.end()) {
        zone.link->publishOutcome(m.player_id, m.seq, std::uint8_t(o->status), o->reason);
        ++counters_.answered_again;
        return;
      }
    }
    if (submit(zone, toLedger(m, zone.tick))) ++counters_.resubmitted;
    return;
  }
  if (m.seq > a.last_transaction_seq + kWindow) {
    ++counters_.too_far;
    return;
  }
  bool early = m.seq > a.last_transaction_seq + 1;
  bool fresh = held_[m.player_id].try_emplace(m.seq, toLedger(m, zone.tick)).second;
  if (early && fresh) repeatLastOutcome(zone, m.player_id);
  release(zone, m.player_id);
}

void Transactions::repeatLastOutcome(PlayerZone& zone, std::uint64_t player) {
  // As TCP's duplicate ack: the newest outcome again tells the client that later ones arrived
  // and one before them is missing, so it resends that one at once rather than at its
  // timeout. Nothing to repeat before this zone decided one (the client's timer covers that).
  auto r = remembered_.find(player);
  if (r == remembered_.end() || r->second.empty()) return;
  const Outcome& o = r->second.back();
  zone.link->publishOutcome(player, o.seq, std::uint8_t(o.status), o.reason);
  ++counters_.gap_notices;
}

void Transactions::release(PlayerZone& zone, std::uint64_t player) {
  auto h = held_.find(player);
  if (h == held_.end()) return;
  std::optional<std::size_t> i = zone.store.avatarOf(player);
  if (!i) {
    held_.erase(h);
    return;
  }
  AvatarData& a = zone.store.avatar[*i];
  auto& waiting = h->second;
  while (!waiting.empty()) {
    auto first = waiting.begin();
    if (first->first <= a.last_transaction_seq) {  // handed over meanwhile (a repeat)
      waiting.erase(first);
      continue;
    }
    if (first->first != a.last_transaction_seq + 1) break;  // a gap: the client resends
    ledger::Transaction tx = first->second;
    tx.tick = zone.tick;
    if (!submit(zone, tx)) break;  // the committer is full: next tick
    a.last_transaction_seq = first->first;
    waiting.erase(first);
  }
  if (waiting.empty()) held_.erase(h);
}

bool Transactions::submit(PlayerZone& zone, const ledger::Transaction& tx) {
  if (committer_ == nullptr) {
    decided(zone, tx, ledger::TxStatus::Failed, "no ledger: the zone runs without --ledger");
    return true;
  }
  switch (committer_->submit(tx)) {
    case ledger::Submit::Accepted:
      ++counters_.submitted;
      in_flight_[tx.player].insert(std::uint32_t(tx.seq));
      return true;
    case ledger::Submit::Invalid:
      decided(zone, tx, ledger::TxStatus::Failed,
              "invalid transaction: " + ledger::invalidReason(tx).value_or("refused"));
      return true;
    case ledger::Submit::Full:
      return false;
    case ledger::Submit::Stopped:
      decided(zone, tx, ledger::TxStatus::Failed, "the zone is shutting down");
      return true;
  }
  return false;
}

void Transactions::publish(PlayerZone& zone) {
  if (committer_ == nullptr) return;
  polled_.clear();
  committer_->poll(polled_);
  for (const ledger::Outcome& o : polled_) {
    auto f = in_flight_.find(o.tx.player);
    if (f != in_flight_.end()) {
      f->second.erase(std::uint32_t(o.tx.seq));
      if (f->second.empty()) in_flight_.erase(f);
    }
    decided(zone, o.tx, o.status, o.reason);
  }
}

void Transactions::decided(PlayerZone& zone, const ledger::Transaction& tx,
                           ledger::TxStatus status, const std::string& reason) {
  switch (status) {
    case ledger::TxStatus::Committed:
      ++counters_.committed;
      break;
    case ledger::TxStatus::AlreadyCommitted:
      ++counters_.already_committed;
      break;
    case ledger::TxStatus::Conflict:
      ++counters_.conflicts;
      break;
    case ledger::TxStatus::Failed:
      ++counters_.failed;
      break;
  }
  auto seq = std::uint32_t(tx.seq);
  std::deque<Outcome>& mine = remembered_[tx.player];
  mine.push_back({seq, status, reason});
  if (mine.size() > kRemembered) mine.pop_front();
  if (zone.link != nullptr) zone.link->publishOutcome(tx.player, seq, std::uint8_t(status), reason);
}

}  // namespace zonesim::zone
