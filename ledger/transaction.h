#pragma once
// One durable transaction of a player: a trade, a loot pick-up, a purchase or a leaderboard
// score. (player, seq) is its idempotency key: the player's client numbers its transactions
// 1, 2, 3 ... and a retry carries the same number, so a commit after a crash applies once.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace zonesim::ledger {

/// What a transaction does; stored as this number, so values are only ever added.
enum class Kind : std::uint8_t { Trade = 1, Loot = 2, Purchase = 3, Score = 4 };

/// "trade", "loot", "purchase", "score".
std::string_view kindName(Kind kind);
/// The kind named by kindName, or nothing.
std::optional<Kind> parseKind(std::string_view name);

/// One transaction. Fields a kind does not use stay 0: a trade gives `item` (or 0 for money
/// only) and `amount` to `counterparty`; loot adds `amount` of `item`; a purchase buys `amount`
/// of `item` for `price`; a score posts `score` to the leaderboard.
struct Transaction {
  std::uint64_t player = 0;  ///< 1 .. 2^63-1: both databases store signed 64-bit integers
  std::uint64_t seq = 0;     ///< 1 .. 2^63-1, per player
  Kind kind = Kind::Loot;
  std::uint64_t item = 0;
  std::int64_t amount = 0;
  std::uint64_t counterparty = 0;
  std::int64_t price = 0;
  std::int64_t score = 0;
  std::uint64_t tick = 0;  ///< the zone tick it was applied at

  bool operator==(const Transaction&) const = default;
};

/// True if a and b ask for the same thing: every field but `tick`. The tick is the zone's
/// record of when it applied the transaction, not part of the player's request: a retry that
/// another zone applies after a handoff or a restart, at another tick, is the same one.
bool sameRequest(const Transaction& a, const Transaction& b);

/// Why `tx` may not be stored (a key out of range, a trade with nobody), or nothing if it may.
std::optional<std::string> invalidReason(const Transaction& tx);

/// "player 7 seq 3 (trade)", for reasons and logs.
std::string describe(const Transaction& tx);

}  // namespace zonesim::ledger
