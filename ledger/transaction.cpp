#include "ledger/transaction.h"

#include <array>
#include <limits>

namespace zonesim::ledger {
namespace {

constexpr std::array<std::pair<Kind, std::string_view>, 4> kKindNames{{
    {Kind::Trade, "trade"},
    {Kind::Loot, "loot"},
    {Kind::Purchase, "purchase"},
    {Kind::Score, "score"},
}};

// SQLite's INTEGER and PostgreSQL's bigint are signed: keys above this would read back negative
// and sort first.
constexpr std::uint64_t kMaxKey = std::uint64_t(std::numeric_limits<std::int64_t>::max());

}  // namespace

std::string_view kindName(Kind kind) {
  for (const auto& [k, name] : kKindNames) {
    if (k == kind) return name;
  }
  return "unknown";
}

std::optional<Kind> parseKind(std::string_view name) {
  for (const auto& [k, n] : kKindNames) {
    if (n == name) return k;
  }
  return std::nullopt;
}

bool sameRequest(const Transaction& a, const Transaction& b) {
  Transaction b_at_a = b;
  b_at_a.tick = a.tick;
  return a == b_at_a;
}

std::optional<std::string> invalidReason(const Transaction& tx) {
  if (tx.player == 0 || tx.player > kMaxKey) return "player id must be 1 .. 2^63-1";
  if (tx.seq == 0 || tx.seq > kMaxKey) return "sequence must be 1 .. 2^63-1";
  if (tx.item > kMaxKey || tx.counterparty > kMaxKey || tx.tick > kMaxKey) {
    return "item, counterparty and tick must be at most 2^63-1";
  }
  if (kindName(tx.kind) == "unknown") return "unknown kind " + std::to_string(int(tx.kind));
  if (tx.kind == Kind::Trade && (tx.counterparty == 0 || tx.counterparty == tx.player)) {
    return "a trade needs a counterparty other than the player";
  }
  return std::nullopt;
}

std::string describe(const Transaction& tx) {
  return "player " + std::to_string(tx.player) + " seq " + std::to_string(tx.seq) + " (" +
         std::string(kindName(tx.kind)) + ")";
}

}  // namespace zonesim::ledger
