#pragma once
// Which kind each simulated player is: the scene's shares (clients.kinds) turned into whole
// players, deterministically, so the same fleet size always gives the same players the same
// kinds (docs/scene-format.md, clients.kinds).

#include <cstddef>
#include <string>
#include <vector>

#include "common/scene_clients.h"

namespace zonesim::clients {

/// The kinds a fleet mixes: the scene's (playerKinds), or with `forced` (a kind name, e.g.
/// client_stub --kind) that one alone with share 1. Throws std::invalid_argument naming the
/// scene's kinds when `forced` is not one of them.
std::vector<PlayerKind> fleetKinds(const ClientProfile& clients, const std::string& forced = {});

/// How many of `players` each kind gets (kinds in the given order): kind k gets the i in
/// 0..players-1 whose (i + 0.5) / players falls in k's slice of the cumulative shares, so
/// 10 players at 0.7 / 0.2 / 0.1 are exactly 7, 2 and 1.
std::vector<std::size_t> kindCounts(const std::vector<PlayerKind>& kinds, std::size_t players);

/// The kind of every player, in player order: the counts of kindCounts, spread over the
/// indices (each next player takes the kind furthest behind (i + 1) * count / players, ties
/// to the earlier kind), so any first players are mixed nearly as the whole fleet. Empty when
/// `kinds` is.
std::vector<PlayerKind> assignKinds(const std::vector<PlayerKind>& kinds, std::size_t players);

}  // namespace zonesim::clients
