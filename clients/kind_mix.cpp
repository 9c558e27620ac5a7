#include "clients/kind_mix.h"

#include <cstdint>
#include <optional>
#include <stdexcept>

namespace zonesim::clients {

std::vector<PlayerKind> fleetKinds(const ClientProfile& clients, const std::string& forced) {
  std::vector<PlayerKind> kinds = playerKinds(clients);
  if (forced.empty()) return kinds;
  std::optional<PlayerKindId> id = playerKindNamed(forced);
  for (PlayerKind k : kinds) {
    if (!id || k.id != *id) continue;
    k.share = 1;
    return {k};
  }
  std::string names;
  for (const PlayerKind& k : kinds)
    names += (names.empty() ? "" : ", ") + std::string(playerKindName(k.id));
  throw std::invalid_argument("'" + forced + "' is not a kind of the scene (its kinds: " + names +
                              ")");
}

std::vector<std::size_t> kindCounts(const std::vector<PlayerKind>& kinds, std::size_t players) {
  std::vector<std::size_t> counts(kinds.size(), 0);
  if (kinds.empty()) return counts;
  for (std::size_t i = 0; i < players; ++i) {
    double at = (double(i) + 0.5) / double(players), upto = 0;
    std::size_t k = 0;
    // The last kind takes what rounding leaves past the final slice (shares sum to 1 +- 1e-6).
    for (; k + 1 < kinds.size(); ++k) {
      upto += kinds[k].share;
      if (at < upto) break;
    }
    ++counts[k];
  }
  return counts;
}

std::vector<PlayerKind> assignKinds(const std::vector<PlayerKind>& kinds, std::size_t players) {
  std::vector<std::size_t> counts = kindCounts(kinds, players), given(kinds.size(), 0);
  std::vector<PlayerKind> out;
  if (kinds.empty()) return out;
  out.reserve(players);
  for (std::size_t i = 0; i < players; ++i) {
    std::size_t best = 0;
    // (i + 1) * count / players - given, times players: whole numbers, so a tie is exact and
    // goes to the earlier kind on every machine.
    std::int64_t behind = INT64_MIN;
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      if (given[k] == counts[k]) continue;
      std::int64_t d = std::int64_t((i + 1) * counts[k]) - std::int64_t(given[k] * players);
      if (d > behind) {
        behind = d;
        best = k;
      }
    }
    ++given[best];
    out.push_back(kinds[best]);
  }
  return out;
}

}  // namespace zonesim::clients
