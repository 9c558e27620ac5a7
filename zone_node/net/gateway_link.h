#pragma once
// The zone's DDS endpoints other than the per-cell streams: player inputs addressed to this
// zone (partition z.<rank>), avatar spawn requests, and ownership announcements.

#include <cstdint>
#include <string_view>
#include <vector>

#include <span>

#include "idl/dds_entity.h"
#include "ledger/store.h"
#include "idl/topics.h"

namespace zonesim::zone {

/// One player input as the gateway sent it.
struct PlayerInputMsg {
  std::uint64_t player_id = 0;
  std::uint32_t seq = 0;
  float move_x = 0, move_z = 0;
};

/// One of a player's transactions as its gateway passed it on (fields as ledger::Transaction).
struct PlayerTransactionMsg {
  std::uint64_t player_id = 0;
  std::uint32_t seq = 0;
  std::uint8_t kind = 0;
  std::uint64_t item = 0;
  std::int64_t amount = 0;
  std::uint64_t counterparty = 0;
  std::int64_t price = 0;
  std::int64_t score = 0;
  std::uint32_t decided = 0;  ///< the client has the outcome of every one up to it
};

/// A player asks for the top `count` of the leaderboard.
struct LeaderboardRequestMsg {
  std::uint64_t player_id = 0;
  std::uint8_t count = 0;
};

/// A request to create a player's avatar at a ground-plane position.
struct SpawnRequestMsg {
  std::uint64_t player_id = 0;
  double x = 0, z = 0;
  std::uint8_t kind = 0;  ///< the player's kind (common/player_kind.h)
  std::uint64_t session = 0;  ///< the gateway session asking
};

/// A player left a gateway session: remove its avatar, unless a newer session asked for it.
struct DespawnRequestMsg {
  std::uint64_t player_id = 0;
  std::uint64_t session = 0;
};

/// An avatar changed owner (from_zone -1: newly created).
struct OwnershipMsg {
  std::uint64_t player_id = 0;
  std::uint64_t avatar_id = 0;
  int from_zone = -1;
  int to_zone = -1;
  std::uint64_t tick = 0;
  std::uint32_t last_input_seq = 0;
};

class GatewayLink {
 public:
  /// Joins the DDS domain as zone `rank` of cluster epoch `epoch` (every announcement carries
  /// it); throws dds::DdsError on failure.
  GatewayLink(int domain, int rank, std::uint32_t epoch);

  dds_entity_t participant() const { return participant_.get(); }
  const dds::Topics& topics() const { return topics_; }

  /// All inputs received since the last call, in arrival order.
  std::vector<PlayerInputMsg> takeInputs();
  /// All spawn requests received since the last call.
  std::vector<SpawnRequestMsg> takeSpawnRequests();
  /// Players whose avatars are to be removed (the player left), since the last call.
  std::vector<DespawnRequestMsg> takeDespawnRequests();
  void announce(const OwnershipMsg& m);
  /// All transactions received since the last call, in arrival order.
  std::vector<PlayerTransactionMsg> takeTransactions();
  /// Tells the gateways what became of a player's transaction (status: ledger::TxStatus);
  /// the reason is cut to what the topic holds.
  void publishOutcome(std::uint64_t player_id, std::uint32_t seq, std::uint8_t status,
                      std::string_view reason);
  /// All leaderboard queries received since the last call.
  std::vector<LeaderboardRequestMsg> takeLeaderboardRequests();
  /// Answers a player's query (at most the topic's 32 rows; reason: why it could not be read).
  void publishLeaderboard(std::uint64_t player_id, std::span<const ledger::LeaderboardRow> rows,
                          std::string_view reason);
  /// Announcements whose write timed out.
  std::uint64_t writeFailures() const { return write_failures_; }

 private:
  dds::Entity participant_;
  dds::Topics topics_;
  dds::PartitionReader inputs_;
  dds::PartitionReader spawns_;
  dds::PartitionReader despawns_;
  dds::PartitionWriter ownership_;
  dds::PartitionReader transactions_;
  dds::PartitionWriter outcomes_;
  dds::PartitionReader leaderboard_requests_;
  dds::PartitionWriter leaderboard_replies_;
  std::uint64_t write_failures_ = 0;
  std::uint32_t epoch_;
};

}  // namespace zonesim::zone
