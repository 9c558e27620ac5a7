#pragma once
// A simulated player's end of its reliable transaction channel (seed 3.1, "TCP for
// transactions"): it makes loot, purchase and score transactions at a steady rate, numbers
// them 1, 2, ... (wire/reliable_stream.h's sender: window, RFC 6298 timeout, backoff), sends
// each again until its outcome comes, and counts every outcome once. An outcome arrives only
// after the owning zone's ledger holds the transaction (zone_node/transactions.h), so it is
// the acknowledgement: the window moves on past every sequence decided without a gap.

#include <cstdint>
#include <functional>
#include <map>
#include <set>

#include "clients/reservoir.h"
#include "common/rng.h"
#include "wire/reliable_stream.h"
#include "wire/wire_encode.h"

namespace zonesim::clients {

/// What one player's channel did.
struct TransactionCounters {
  std::uint64_t made = 0;       ///< transactions created
  std::uint64_t sent = 0;       ///< first sends
  std::uint64_t resent = 0;     ///< sends again (timeout, or a new session)
  std::uint64_t committed = 0;  ///< outcomes "committed" or "already committed": durable
  std::uint64_t already_committed = 0;  ///< of those, a retry the ledger had stored before
  std::uint64_t conflicts = 0, failed = 0;
  std::uint64_t outcome_repeats = 0;  ///< a second outcome for a sequence already decided
  std::uint64_t outcome_unknown = 0;  ///< an outcome for a sequence never sent
  std::uint64_t refused_window_full = 0;  ///< not made: 64 undecided already
  Reservoir latency_ms;  ///< from the first send to the outcome
};

class TransactionStream {
 public:
  /// rate_per_s: transactions a second (0: none); seed: this player's content stream.
  TransactionStream(double rate_per_s, std::uint64_t seed, std::int64_t start_ns);

  bool active() const { return period_ns_ > 0; }
  /// Makes what is due by now_ns and hands every transaction due a (re)send to send(); returns
  /// when it next has something to do (INT64_MAX: nothing).
  std::int64_t due(std::int64_t now_ns,
                   const std::function<void(const gateway::TransactionInfo&)>& send);
  /// The outcome of transaction seq (status: ledger::TxStatus).
  void onOutcome(std::uint32_t seq, std::uint8_t status, std::int64_t now_ns);
  /// A new session at a gateway (resumed): everything undecided goes again now.
  void onNewSession() { sender_.resendAll(); }
  /// The player starts over under a new id: a new channel from seq 1 (what was undecided is
  /// lost with the old player, and counted failed).
  void restart(std::int64_t now_ns);

  /// Undecided transactions.
  std::size_t pending() const { return pending_.size(); }
  const TransactionCounters& counters() const { return counters_; }

 private:
  gateway::TransactionInfo make(std::uint32_t seq);

  std::int64_t period_ns_;
  std::int64_t next_make_ns_;
  Pcg32 rng_;
  gateway::ReliableSender sender_;
  std::map<std::uint32_t, gateway::TransactionInfo> pending_;  // sent or to send, undecided
  std::map<std::uint32_t, std::int64_t> first_sent_ns_;
  std::set<std::uint32_t> timed_;          // sent first with all before decided: RTT samples
  std::set<std::uint32_t> decided_early_;  // decided above a gap, not yet acknowledged
  std::uint32_t decided_ = 0;              // every sequence up to it decided
  TransactionCounters counters_;
};

}  // namespace zonesim::clients
