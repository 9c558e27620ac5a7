#pragma once
// The server back end: PostgreSQL through libpq. A batch is one transaction of one array
// INSERT ... ON CONFLICT (player, seq) DO NOTHING RETURNING, then one read of the keys that were
// there already, to compare their content. A lost connection fails the operation as
// Unavailable and the next one connects again. libpq-fe.h stays in the .cpp.

#include <memory>
#include <string>

#include "ledger/store.h"

namespace zonesim::ledger {

struct PostgresOptions {
  /// A libpq connection string: "host=/tmp/sock dbname=ledger" or "postgresql://host/db".
  std::string conninfo;
};

class PostgresStore final : public LedgerStore {
 public:
  /// Connects and creates or checks the schema. Throws std::invalid_argument for a connection
  /// string libpq cannot parse, StoreError (Unavailable) when the server cannot be reached.
  explicit PostgresStore(const PostgresOptions& options);
  ~PostgresStore() override;
  PostgresStore(const PostgresStore&) = delete;
  PostgresStore& operator=(const PostgresStore&) = delete;

  std::string_view backend() const override { return "postgres"; }
  std::vector<TxResult> commit(std::span<const Transaction> batch) override;
  std::uint64_t highestSequence(std::uint64_t player) override;
  std::vector<LeaderboardRow> leaderboard(std::size_t n) override;
  LedgerCounts counts() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace zonesim::ledger
