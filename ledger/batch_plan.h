#pragma once
// The part of a commit every back end shares: check each transaction and find repeats of a key
// within the batch, so that the database writes each key at most once; then, from what the
// database holds for each key, the result of every transaction (store.h).

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "ledger/store.h"

namespace zonesim::ledger {

/// What the back end must write for a batch.
struct BatchPlan {
  static constexpr std::size_t kInvalid = std::size_t(-1);
  /// Indices of the transactions to write ("insert unless the key is stored"), each key once,
  /// in batch order.
  std::vector<std::size_t> to_store;
  /// Per transaction: its slot in to_store (its own, or its key's first), or kInvalid.
  std::vector<std::size_t> slot;
  /// Per transaction: why it is invalid, empty if valid.
  std::vector<std::string> invalid;
};

/// What the database held for one written key after the write.
struct KeyWrite {
  bool inserted = false;  ///< this batch stored it
  Transaction stored;     ///< the stored content (the transaction itself when inserted)
};

BatchPlan planBatch(std::span<const Transaction> batch);

/// One result per transaction, given one KeyWrite per entry of plan.to_store: the transaction
/// that inserted its key is Committed; any other with the key is AlreadyCommitted if equal to
/// the stored content, else a Conflict.
std::vector<TxResult> batchResults(std::span<const Transaction> batch, const BatchPlan& plan,
                                   std::span<const KeyWrite> writes);

}  // namespace zonesim::ledger
