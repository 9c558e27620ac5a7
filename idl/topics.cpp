#include "idl/topics.h"

#include "zonesim.h"

namespace zonesim::dds {

Topics makeTopics(dds_entity_t participant) {
  Topics t;
  t.cell_updates = makeTopic(participant, &zonesim_dds_CellUpdateBatch_desc, "zs_cell_updates", nullptr);
  t.cell_keyframes = makeTopic(participant, &zonesim_dds_CellKeyframe_desc, "zs_cell_keyframes", nullptr);
  t.ownership = makeTopic(participant, &zonesim_dds_OwnershipEvent_desc, "zs_ownership", nullptr);
  t.player_input = makeTopic(participant, &zonesim_dds_PlayerInput_desc, "zs_player_input", nullptr);
  t.spawn_requests = makeTopic(participant, &zonesim_dds_SpawnRequest_desc, "zs_spawn_requests", nullptr);
  t.despawn_requests =
      makeTopic(participant, &zonesim_dds_DespawnRequest_desc, "zs_despawn_requests", nullptr);
  t.gateway_load =
      makeTopic(participant, &zonesim_dds_GatewayLoad_desc, "zs_gateway_load", nullptr);
  t.player_transactions = makeTopic(participant, &zonesim_dds_PlayerTransaction_desc,
                                    "zs_player_transactions", nullptr);
  t.transaction_outcomes = makeTopic(participant, &zonesim_dds_TransactionOutcome_desc,
                                     "zs_transaction_outcomes", nullptr);
  t.leaderboard_requests = makeTopic(participant, &zonesim_dds_LeaderboardRequest_desc,
                                     "zs_leaderboard_requests", nullptr);
  t.leaderboard_replies = makeTopic(participant, &zonesim_dds_LeaderboardReply_desc,
                                    "zs_leaderboard_replies", nullptr);
  return t;
}

}  // namespace zonesim::dds
