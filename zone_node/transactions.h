#pragma once
// The zone's end of each player's reliable transaction channel (seed 3.1, "TCP for
// transactions"). The client numbers its transactions 1, 2, ... and sends each again until its
// outcome comes back; its gateway passes every copy on to the avatar's owning zone. Here:
// - each goes to the ledger's committer (ledger/committer.h: the tick never waits for the
//   database) once, in sequence order; an early one waits, up to kWindow ahead, for the gap
//   before it to fill (the client resends what was lost);
// - the last one handed over is the avatar's (AvatarData::last_transaction_seq): it migrates
//   with the avatar and is in every checkpoint, so the next owner goes on from it; a zone
//   restored from an older checkpoint goes on from where the client says every outcome
//   reached it (Transaction::decided), since none of those is sent again;
// - an outcome is published once the database holds the transaction (committed or already
//   committed) or refused it, and remembered: a repeat whose outcome was lost is answered from
//   memory or, where this zone has none (it took the avatar over, or restarted), handed to the
//   ledger again, whose (player, seq) key stores nothing twice (AlreadyCommitted);
// - an early arrival repeats the last outcome (a duplicate ack): the client resends the
//   missing one at once;
// - a transaction for a player whose avatar is not here is dropped and counted: the client
//   sends it again, and its gateway routes it to the new owner.

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>

#include "ledger/committer.h"

namespace zonesim::zone {

struct PlayerZone;
struct PlayerTransactionMsg;

/// What the channel did, cumulative.
struct TransactionCounters {
  std::uint64_t received = 0;        ///< copies taken from the gateways
  std::uint64_t submitted = 0;       ///< handed to the ledger
  std::uint64_t resubmitted = 0;     ///< of those, repeats with no outcome known here
  std::uint64_t answered_again = 0;  ///< repeats answered from memory
  std::uint64_t not_here = 0;        ///< for a player whose avatar is not in this zone
  std::uint64_t too_far = 0;         ///< more than kWindow past the last handed over
  std::uint64_t gap_notices = 0;     ///< last outcomes repeated for an early arrival
  std::uint64_t fast_forwards = 0;   ///< went on to the client's decided point (restored zone)
  std::uint64_t committed = 0, already_committed = 0, conflicts = 0, failed = 0;  ///< outcomes
};

class Transactions {
 public:
  /// Outcomes remembered per player, and how far past the last handed over one is held.
  static constexpr std::size_t kRemembered = 128;
  static constexpr std::uint32_t kWindow = 64;

  /// committer: the ledger's; null for a zone without one, whose transactions all fail with a
  /// reason the client is told.
  explicit Transactions(std::unique_ptr<ledger::LedgerCommitter> committer);
  ~Transactions();

  /// Input phase: takes the gateways' transactions, hands those whose turn has come to the
  /// ledger, and answers repeats.
  void input(PlayerZone& zone);
  /// Publish phase: tells the gateways the outcomes the ledger decided since the last call.
  void publish(PlayerZone& zone);
  const TransactionCounters& counters() const { return counters_; }
  /// The committer's own counters (zeros without a ledger).
  ledger::CommitterStats ledgerStats() const;

 private:
  void take(PlayerZone& zone, const PlayerTransactionMsg& m);
  /// An early one arrived: repeats the player's newest outcome.
  void repeatLastOutcome(PlayerZone& zone, std::uint64_t player);
  /// Hands player's held transactions to the ledger while the next in sequence is there.
  void release(PlayerZone& zone, std::uint64_t player);
  /// False if the committer is full (try again next tick).
  bool submit(PlayerZone& zone, const ledger::Transaction& tx);
  void decided(PlayerZone& zone, const ledger::Transaction& tx, ledger::TxStatus status,
               const std::string& reason);

  struct Outcome {
    std::uint32_t seq;
    ledger::TxStatus status;
    std::string reason;
  };
  std::unique_ptr<ledger::LedgerCommitter> committer_;
  std::map<std::uint64_t, std::map<std::uint32_t, ledger::Transaction>> held_;  // player -> seq
  std::unordered_map<std::uint64_t, std::set<std::uint32_t>> in_flight_;  // at the committer
  std::unordered_map<std::uint64_t, std::deque<Outcome>> remembered_;     // newest last
  std::vector<ledger::Outcome> polled_;
  TransactionCounters counters_;
};

}  // namespace zonesim::zone
