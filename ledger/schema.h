#pragma once
// The ledger's schema, the same table in both back ends: one row per transaction, keyed by
// (player, seq). Version 1; a database with a newer version is refused, never altered.

namespace zonesim::ledger::schema {

inline constexpr int kVersion = 1;

/// Columns in the order every INSERT and SELECT of a whole row uses.
inline constexpr const char* kColumns =
    "player, seq, kind, item, amount, counterparty, price, score, tick";

inline constexpr const char* kCreateMeta =
    "CREATE TABLE IF NOT EXISTS ledger_meta (key TEXT PRIMARY KEY, value BIGINT NOT NULL)";

inline constexpr const char* kCreateTx =
    "CREATE TABLE IF NOT EXISTS ledger_tx ("
    " player BIGINT NOT NULL, seq BIGINT NOT NULL, kind SMALLINT NOT NULL,"
    " item BIGINT NOT NULL, amount BIGINT NOT NULL, counterparty BIGINT NOT NULL,"
    " price BIGINT NOT NULL, score BIGINT NOT NULL, tick BIGINT NOT NULL,"
    " PRIMARY KEY (player, seq))";

// The leaderboard reads only scores; a partial index keeps it off the other rows.
inline constexpr const char* kCreateScoreIndex =
    "CREATE INDEX IF NOT EXISTS ledger_tx_scores ON ledger_tx (player, score DESC, tick)"
    " WHERE kind = 4";

/// Best score per player (first reached wins), then the top rows; one parameter: the limit.
/// Shared by both back ends, which append their own SQL parameter marker for the limit:
/// "$1" in PostgreSQL, "?1" in SQLite.
inline constexpr const char* kLeaderboardBody =
    "SELECT player, score, tick FROM ("
    " SELECT player, score, tick, ROW_NUMBER() OVER"
    " (PARTITION BY player ORDER BY score DESC, tick ASC, seq ASC) AS rank_in_player"
    " FROM ledger_tx WHERE kind = 4) AS best"
    " WHERE rank_in_player = 1 ORDER BY score DESC, tick ASC, player ASC LIMIT ";

inline constexpr const char* kCounts = "SELECT kind, COUNT(*) FROM ledger_tx GROUP BY kind";

}  // namespace zonesim::ledger::schema
