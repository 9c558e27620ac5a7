#pragma once
// The DDS topics of a zonesim domain, created once per participant with their agreed names.
//   zs_cell_updates    CellUpdateBatch  partition c.<ix>.<iz>  zone -> gateway, cellUpdateQos
//   zs_cell_keyframes  CellKeyframe     partition c.<ix>.<iz>  zone -> gateway, cellKeyframeQos
//   zs_ownership       OwnershipEvent   default partition      zone -> gateway, reliableKeepAll
//   zs_player_input    PlayerInput      partition z.<rank>     gateway -> zone, reliableKeepAll
//   zs_spawn_requests  SpawnRequest     default partition      gateway -> zones, reliableKeepAll
//   zs_despawn_requests DespawnRequest  default partition      gateway -> zones, reliableKeepAll
//   zs_player_transactions PlayerTransaction partition z.<rank> gateway -> zone, reliableKeepAll
//   zs_transaction_outcomes TransactionOutcome default partition zone -> gateways, reliableKeepAll
//   zs_leaderboard_requests LeaderboardRequest partition z.<rank> gateway -> zone, reliableKeepAll
//   zs_leaderboard_replies LeaderboardReply default partition zone -> gateways, reliableKeepAll
//   zs_gateway_load    GatewayLoad      default partition      gateway -> lobby, gatewayLoadQos

#include <cstddef>

#include "idl/dds_entity.h"

namespace zonesim::dds {

/// Rows a LeaderboardReply holds: the bound of its sequence in idl/zonesim.idl, and what a
/// player may ask for (wire/wire_verify.h, kMaxLeaderboardRows).
inline constexpr std::size_t kLeaderboardRows = 32;

struct Topics {
  Entity cell_updates;
  Entity cell_keyframes;
  Entity ownership;
  Entity player_input;
  Entity spawn_requests;
  Entity despawn_requests;
  Entity gateway_load;
  Entity player_transactions;
  Entity transaction_outcomes;
  Entity leaderboard_requests;
  Entity leaderboard_replies;
};

/// Creates all zonesim topics on the participant.
Topics makeTopics(dds_entity_t participant);

}  // namespace zonesim::dds
