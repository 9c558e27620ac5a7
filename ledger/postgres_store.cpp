#include "ledger/postgres_store.h"

#include <libpq-fe.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "ledger/batch_plan.h"
#include "ledger/schema.h"

namespace zonesim::ledger {
namespace {

static_assert(int(Kind::Score) == 4, "schema.h's score queries say kind = 4");

// libpq's messages end in a newline and may span lines; a reason is one line.
std::string oneLine(const char* message) {
  std::string out = message ? message : "";
  for (char& c : out) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// Retryable: the server is down, restarting, out of connections, or the transaction lost a
// race. 53100 is disk_full. Anything else is an Error.
StoreFailure failureOf(const char* sqlstate, bool connection_lost) {
  if (connection_lost || !sqlstate) return StoreFailure::Unavailable;
  std::string_view s(sqlstate);
  if (s == "53100") return StoreFailure::Full;
  if (s.starts_with("08") || s == "57P01" || s == "57P02" || s == "57P03" || s == "53300" ||
      s == "53200" || s == "40001" || s == "40P01") {
    return StoreFailure::Unavailable;
  }
  return StoreFailure::Error;
}

struct ResultPtr {
  PGresult* res = nullptr;
  explicit ResultPtr(PGresult* r) : res(r) {}
  ResultPtr(ResultPtr&& other) noexcept : res(std::exchange(other.res, nullptr)) {}
  ResultPtr& operator=(ResultPtr&&) = delete;
  ~ResultPtr() { PQclear(res); }
};

std::int64_t toInt(const char* text) {
  std::int64_t v = 0;
  std::string_view s(text);
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) {
    throw StoreError(StoreFailure::Error,
                     "postgres: not an integer in a result: " + std::string(s.substr(0, 40)));
  }
  return v;
}

// A PostgreSQL array literal of integers, "{1,2,3}".
template <typename Get>
std::string arrayOf(std::span<const Transaction> batch, const std::vector<std::size_t>& rows,
                    Get get) {
  std::string out = "{";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i) out += ',';
    out += std::to_string(get(batch[rows[i]]));
  }
  out += '}';
  return out;
}

// The parts of a connection string that say where, never the password.
std::string whereOf(const std::string& conninfo) {
  char* err = nullptr;
  PQconninfoOption* options = PQconninfoParse(conninfo.c_str(), &err);
  if (!options) {
    std::string why = oneLine(err);
    PQfreemem(err);
    throw std::invalid_argument("postgres: bad connection string: " + why);
  }
  std::string out;
  for (PQconninfoOption* o = options; o->keyword; ++o) {
    std::string_view key(o->keyword);
    if (!o->val || !(key == "host" || key == "hostaddr" || key == "port" || key == "dbname" ||
                     key == "user")) {
      continue;
    }
    if (!out.empty()) out += ' ';
    out += std::string(key) + "=" + o->val;
  }
  PQconninfoFree(options);
  return out.empty() ? "defaults" : out;
}

constexpr const char* kInsert = "ledger_insert";
constexpr const char* kSelectKeys = "ledger_select_keys";
constexpr const char* kHighest = "ledger_highest";
constexpr const char* kLeaderboard = "ledger_leaderboard";
constexpr const char* kCounts = "ledger_counts";

}  // namespace

struct PostgresStore::Impl {
  PostgresOptions options;
  std::string where;
  PGconn* conn = nullptr;

  ~Impl() { PQfinish(conn); }

  std::string prefix() const { return "postgres (" + where + "): "; }

  [[noreturn]] void fail(const std::string& what, const PGresult* res) {
    bool lost = PQstatus(conn) != CONNECTION_OK;
    const char* state = res ? PQresultErrorField(res, PG_DIAG_SQLSTATE) : nullptr;
    std::string message = res ? oneLine(PQresultErrorMessage(res)) : "";
    if (message.empty()) message = oneLine(PQerrorMessage(conn));
    if (lost) message = "connection lost: " + message;
    throw StoreError(failureOf(state, lost), prefix() + what + ": " + message);
  }

  // Runs a command or query; throws on anything but success.
  ResultPtr run(const char* what, const char* sql) {
    ResultPtr res(PQexec(conn, sql));
    check(what, res);
    return res;
  }

  ResultPtr runPrepared(const char* what, const char* name, std::vector<std::string> params) {
    std::vector<const char*> values;
    for (const auto& p : params) values.push_back(p.c_str());
    ResultPtr res(
        PQexecPrepared(conn, name, int(values.size()), values.data(), nullptr, nullptr, 0));
    check(what, res);
    return res;
  }

  void check(const char* what, const ResultPtr& res) {
    auto status = PQresultStatus(res.res);
    if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK) fail(what, res.res);
  }

  void rollback() noexcept {
    if (PQstatus(conn) == CONNECTION_OK && PQtransactionStatus(conn) != PQTRANS_IDLE) {
      PQclear(PQexec(conn, "ROLLBACK"));
    }
  }

  void prepare(const char* name, const std::string& sql) {
    ResultPtr res(PQprepare(conn, name, sql.c_str(), 0, nullptr));
    check("prepare", res);
  }

  // (Re)connects when there is no good connection: a server restart leaves the old one BAD.
  void ensureConnected() {
    if (conn && PQstatus(conn) == CONNECTION_OK) return;
    PQfinish(conn);
    conn = PQconnectdb(options.conninfo.c_str());
    if (PQstatus(conn) != CONNECTION_OK) {
      std::string why = oneLine(PQerrorMessage(conn));
      PQfinish(conn);
      conn = nullptr;
      throw StoreError(StoreFailure::Unavailable, prefix() + "cannot connect: " + why);
    }
    // The server's notices (a shutdown's "terminating connection") would go to stderr; the
    // errors that matter come back as results.
    PQsetNoticeProcessor(
        conn, [](void*, const char*) {}, nullptr);
    migrate();
    const std::string columns = schema::kColumns;
    prepare(kInsert,
            "INSERT INTO ledger_tx (" + columns +
                ") SELECT * FROM unnest($1::bigint[], $2::bigint[], $3::smallint[],"
                " $4::bigint[], $5::bigint[], $6::bigint[], $7::bigint[], $8::bigint[],"
                " $9::bigint[]) ON CONFLICT (player, seq) DO NOTHING RETURNING player, seq");
    prepare(kSelectKeys, "SELECT " + columns +
                             " FROM ledger_tx WHERE (player, seq) IN"
                             " (SELECT * FROM unnest($1::bigint[], $2::bigint[]))");
    prepare(kHighest, "SELECT COALESCE(MAX(seq), 0) FROM ledger_tx WHERE player = $1");
    prepare(kLeaderboard, std::string(schema::kLeaderboardBody) + "$1");
    prepare(kCounts, schema::kCounts);
  }

  // Two stores opening one fresh database at once would race on CREATE TABLE IF NOT EXISTS:
  // an advisory lock for the transaction serialises them.
  void migrate() {
    try {
      run("begin schema transaction", "BEGIN");
      run("lock the schema", "SELECT pg_advisory_xact_lock(7210001)");
      run("create ledger_meta", schema::kCreateMeta);
      run("create ledger_tx", schema::kCreateTx);
      run("create the score index", schema::kCreateScoreIndex);
      ResultPtr version = run("read the schema version",
                              "SELECT value FROM ledger_meta WHERE key = 'schema_version'");
      if (PQntuples(version.res) == 1) {
        auto found = toInt(PQgetvalue(version.res, 0, 0));
        if (found != schema::kVersion) {
          throw StoreError(StoreFailure::Error, prefix() + "schema version " +
                                                    std::to_string(found) + ", this build knows " +
                                                    std::to_string(schema::kVersion));
        }
      } else {
        std::string insert = "INSERT INTO ledger_meta (key, value) VALUES ('schema_version', " +
                             std::to_string(schema::kVersion) + ")";
        run("write the schema version", insert.c_str());
      }
      run("commit the schema", "COMMIT");
    } catch (...) {
      rollback();
      throw;
    }
  }

  Transaction rowOf(const PGresult* res, int row) const {
    auto col = [&](int c) { return toInt(PQgetvalue(res, row, c)); };
    Transaction tx;
    tx.player = std::uint64_t(col(0));
    tx.seq = std::uint64_t(col(1));
    tx.kind = Kind(col(2));
    tx.item = std::uint64_t(col(3));
    tx.amount = col(4);
    tx.counterparty = std::uint64_t(col(5));
    tx.price = col(6);
    tx.score = col(7);
    tx.tick = std::uint64_t(col(8));
    return tx;
  }

  std::vector<KeyWrite> write(std::span<const Transaction> batch, const BatchPlan& plan) {
    const auto& rows = plan.to_store;
    ResultPtr inserted = runPrepared(
        "insert", kInsert,
        {arrayOf(batch, rows, [](const Transaction& t) { return std::int64_t(t.player); }),
         arrayOf(batch, rows, [](const Transaction& t) { return std::int64_t(t.seq); }),
         arrayOf(batch, rows, [](const Transaction& t) { return int(t.kind); }),
         arrayOf(batch, rows, [](const Transaction& t) { return std::int64_t(t.item); }),
         arrayOf(batch, rows, [](const Transaction& t) { return t.amount; }),
         arrayOf(batch, rows, [](const Transaction& t) { return std::int64_t(t.counterparty); }),
         arrayOf(batch, rows, [](const Transaction& t) { return t.price; }),
         arrayOf(batch, rows, [](const Transaction& t) { return t.score; }),
         arrayOf(batch, rows, [](const Transaction& t) { return std::int64_t(t.tick); })});
    using Key = std::pair<std::uint64_t, std::uint64_t>;
    std::map<Key, bool> was_inserted;
    for (int r = 0; r < PQntuples(inserted.res); ++r) {
      was_inserted[{std::uint64_t(toInt(PQgetvalue(inserted.res, r, 0))),
                    std::uint64_t(toInt(PQgetvalue(inserted.res, r, 1)))}] = true;
    }
    std::vector<KeyWrite> writes(rows.size());
    std::vector<std::size_t> existing;  // indices into batch of keys stored before
    std::map<Key, std::size_t> slot_of_existing;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Transaction& tx = batch[rows[k]];
      if (was_inserted.count({tx.player, tx.seq})) {
        writes[k] = {true, tx};
      } else {
        existing.push_back(rows[k]);
        slot_of_existing[{tx.player, tx.seq}] = k;
      }
    }
    if (existing.empty()) return writes;
    ResultPtr stored = runPrepared(
        "read stored transactions", kSelectKeys,
        {arrayOf(batch, existing, [](const Transaction& t) { return std::int64_t(t.player); }),
         arrayOf(batch, existing, [](const Transaction& t) { return std::int64_t(t.seq); })});
    std::size_t found = 0;
    for (int r = 0; r < PQntuples(stored.res); ++r) {
      Transaction tx = rowOf(stored.res, r);
      auto it = slot_of_existing.find({tx.player, tx.seq});
      if (it == slot_of_existing.end()) continue;
      writes[it->second] = {false, tx};
      ++found;
    }
    if (found != existing.size()) {
      throw StoreError(StoreFailure::Error,
                       prefix() + "a conflicting insert found no row for some keys");
    }
    return writes;
  }
};

PostgresStore::PostgresStore(const PostgresOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->where = whereOf(options.conninfo);
  impl_->ensureConnected();
}

PostgresStore::~PostgresStore() = default;

std::vector<TxResult> PostgresStore::commit(std::span<const Transaction> batch) {
  BatchPlan plan = planBatch(batch);
  std::vector<KeyWrite> writes;
  if (!plan.to_store.empty()) {
    impl_->ensureConnected();
    try {
      impl_->run("begin", "BEGIN");
      writes = impl_->write(batch, plan);
      // A connection lost during COMMIT leaves the outcome unknown; the retry finds out, since
      // the keys make it idempotent.
      impl_->run("commit", "COMMIT");
    } catch (...) {
      impl_->rollback();
      throw;
    }
  }
  return batchResults(batch, plan, writes);
}

std::uint64_t PostgresStore::highestSequence(std::uint64_t player) {
  impl_->ensureConnected();
  ResultPtr res = impl_->runPrepared("read the highest sequence", kHighest,
                                     {std::to_string(std::int64_t(player))});
  return std::uint64_t(toInt(PQgetvalue(res.res, 0, 0)));
}

std::vector<LeaderboardRow> PostgresStore::leaderboard(std::size_t n) {
  impl_->ensureConnected();
  ResultPtr res = impl_->runPrepared("read the leaderboard", kLeaderboard,
                                     {std::to_string(std::min<std::size_t>(n, INT64_MAX))});
  std::vector<LeaderboardRow> rows;
  for (int r = 0; r < PQntuples(res.res); ++r) {
    rows.push_back({std::uint64_t(toInt(PQgetvalue(res.res, r, 0))),
                    toInt(PQgetvalue(res.res, r, 1)),
                    std::uint64_t(toInt(PQgetvalue(res.res, r, 2)))});
  }
  return rows;
}

LedgerCounts PostgresStore::counts() {
  impl_->ensureConnected();
  ResultPtr res = impl_->runPrepared("count transactions", kCounts, {});
  LedgerCounts counts;
  for (int r = 0; r < PQntuples(res.res); ++r) {
    auto kind = toInt(PQgetvalue(res.res, r, 0));
    auto n = std::uint64_t(toInt(PQgetvalue(res.res, r, 1)));
    counts.total += n;
    if (kind > 0 && kind < 5) counts.by_kind[kind] = n;
  }
  return counts;
}

}  // namespace zonesim::ledger
