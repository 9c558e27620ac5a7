#pragma once
// The gateway's DDS side: spawn requests and inputs out to the zones, ownership events and
// per-cell state in. One subscriber+reader pair (updates, keyframes) per subscribed interest
// cell, since Cyclone cannot change a subscriber's partitions; one publisher+writer per zone
// partition for inputs. All reads are dds_take loops over loaned samples, once per gateway tick.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "gateway/datagram_handler.h"
#include "gateway/epoch_timeline.h"
#include "gateway/world_cache.h"
#include "gateway/zone_clock.h"
#include "idl/dds_entity.h"
#include "idl/dds_qos.h"
#include "idl/topics.h"
#include "zonesim.h"

namespace zonesim::gateway {

/// A zone's answer to one of a player's transactions (status as ledger::TxStatus).
struct TransactionOutcomeMsg {
  std::uint64_t player_id = 0;
  std::uint32_t seq = 0;
  std::uint8_t status = 0;
  std::string reason;
};

/// A zone's answer to a player's leaderboard query.
struct LeaderboardReplyMsg {
  std::uint64_t player_id = 0;
  std::vector<LeaderboardLine> rows;
  std::string reason;
};

class ZoneLink {
 public:
  /// Joins the domain; spawn requests are held until expected_zones readers listen, so the
  /// zone that should create an avatar is never missed because it had not been discovered yet.
  ZoneLink(dds_domainid_t domain, int expected_zones);

  /// Publishes (or holds) a request for an avatar.
  void requestSpawn(const SpawnCommand& c);
  /// Writes held spawn requests if enough zones listen now; returns how many were written.
  std::size_t flushSpawns();
  std::size_t heldSpawns() const { return held_spawns_.size(); }
  /// The player left session_id: drops the session's held spawn request, or asks the zones to
  /// remove its avatar (which they do only if no newer session asked for it).
  void requestDespawn(std::uint64_t player_id, std::uint64_t session_id);
  /// Writes one input on the owning zone's partition; false if the write failed (timed out).
  bool sendInput(const InputCommand& c);
  /// Writes one transaction on the owning zone's partition; false if the write failed (the
  /// client sends it again).
  bool sendTransaction(const TransactionCommand& c);
  /// Takes every zone's pending transaction outcomes, for whichever gateway's players.
  std::vector<TransactionOutcomeMsg> takeOutcomes();
  /// Asks the player's avatar's zone for the leaderboard; false if the write failed.
  bool askLeaderboard(const LeaderboardCommand& c);
  /// Takes every zone's pending leaderboard answers, for whichever gateway's players.
  std::vector<LeaderboardReplyMsg> takeLeaderboards();

  /// Creates the readers of cell (ix, iz) with id cell; nothing if already there.
  void subscribeCell(int cell, int ix, int iz);
  /// Deletes the readers of a cell; nothing if not there.
  void unsubscribeCell(int cell);
  std::size_t subscribedCells() const { return cells_.size(); }
  bool subscribed(int cell) const { return cells_.contains(cell); }

  /// Takes every pending ownership event.
  std::vector<zonesim_dds_OwnershipEvent> takeOwnership();
  /// The participant and topics, for the gateway's other publications (its load report).
  dds_entity_t participant() const { return participant_.get(); }
  const dds::Topics& topics() const { return topics_; }
  /// Takes every pending cell sample into the cache and the clock, on the timeline's ticks
  /// (samples of an old epoch are dropped there); returns samples taken.
  std::size_t takeCells(WorldCache& cache, ZoneClock& clock, EpochTimeline& timeline,
                        std::int64_t now_ns);

 private:
  struct CellReaders {
    dds::PartitionReader updates, keyframes;
  };
  /// The writer of `topic` on zone's partition, created on first use.
  dds::PartitionWriter& zoneWriter(std::map<int, dds::PartitionWriter>& writers,
                                   dds_entity_t topic, int zone);

  int expected_zones_;
  // Declared first so it is deleted last; deleting it would delete every child anyway.
  dds::Entity participant_;
  dds::Topics topics_;
  dds::Qos keep_all_qos_, input_qos_, update_qos_, keyframe_qos_;
  dds::PartitionWriter spawn_writer_;
  dds::PartitionWriter despawn_writer_;
  dds::PartitionReader ownership_reader_;
  dds::PartitionReader outcome_reader_;
  dds::PartitionReader leaderboard_reader_;
  std::map<int, dds::PartitionWriter> input_writers_;
  std::map<int, dds::PartitionWriter> transaction_writers_;
  std::map<int, dds::PartitionWriter> leaderboard_writers_;
  std::map<int, CellReaders> cells_;
  std::vector<SpawnCommand> held_spawns_;
};

}  // namespace zonesim::gateway
