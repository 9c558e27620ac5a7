#include "gateway/zone_link.h"

#include <algorithm>

#include "common/log.h"
#include "idl/dds_take.h"

namespace zonesim::gateway {

static_assert(kMaxLeaderboardRows == dds::kLeaderboardRows,
              "a player may ask for as many rows as the zones' reply holds");

ZoneLink::ZoneLink(dds_domainid_t domain, int expected_zones)
    : expected_zones_(std::max(1, expected_zones)),
      participant_(dds::makeParticipant(domain)),
      topics_(dds::makeTopics(participant_.get())),
      keep_all_qos_(dds::reliableKeepAllQos()),
      input_qos_(dds::playerInputQos()),
      update_qos_(dds::cellUpdateQos()),
      keyframe_qos_(dds::cellKeyframeQos()) {
  spawn_writer_ = dds::makePartitionWriter(participant_.get(), topics_.spawn_requests.get(), "",
                                           keep_all_qos_.get());
  despawn_writer_ = dds::makePartitionWriter(participant_.get(), topics_.despawn_requests.get(), "",
                                             keep_all_qos_.get());
  ownership_reader_ = dds::makePartitionReader(participant_.get(), topics_.ownership.get(), "",
                                               keep_all_qos_.get());
  outcome_reader_ = dds::makePartitionReader(
      participant_.get(), topics_.transaction_outcomes.get(), "", keep_all_qos_.get());
  leaderboard_reader_ = dds::makePartitionReader(
      participant_.get(), topics_.leaderboard_replies.get(), "", keep_all_qos_.get());
  // Input writers for the zones we expect, created now so they are matched before the first
  // input: an input written before its reader is discovered would be lost.
  for (int z = 0; z < expected_zones_; ++z) {
    zoneWriter(input_writers_, topics_.player_input.get(), z);
    zoneWriter(transaction_writers_, topics_.player_transactions.get(), z);
  }
}

void ZoneLink::requestSpawn(const SpawnCommand& c) {
  held_spawns_.push_back(c);
  flushSpawns();
}

std::size_t ZoneLink::flushSpawns() {
  if (held_spawns_.empty()) return 0;
  dds_publication_matched_status_t st{};
  dds::check(dds_get_publication_matched_status(spawn_writer_.writer.get(), &st),
             "dds_get_publication_matched_status");
  if (int(st.current_count) < expected_zones_) return 0;
  std::size_t written = 0;
  for (const SpawnCommand& c : held_spawns_) {
    zonesim_dds_SpawnRequest r{};
    r.player_id = c.player_id;
    r.position = {c.x, c.y, c.z};
    r.kind = c.kind;
    r.session = c.session_id;
    // A write that times out (a zone not keeping up) is retried on the next tick.
    if (dds_write(spawn_writer_.writer.get(), &r) < 0) break;
    ++written;
  }
  held_spawns_.erase(held_spawns_.begin(), held_spawns_.begin() + long(written));
  return written;
}

void ZoneLink::requestDespawn(std::uint64_t player_id, std::uint64_t session_id) {
  auto held = std::find_if(held_spawns_.begin(), held_spawns_.end(), [&](const SpawnCommand& c) {
    return c.player_id == player_id && c.session_id == session_id;
  });
  if (held != held_spawns_.end()) {
    held_spawns_.erase(held);  // never reached a zone: nothing to remove there
    return;
  }
  zonesim_dds_DespawnRequest r{};
  r.player_id = player_id;
  r.session = session_id;
  // A zone that stopped reading makes the write time out; the gateway must not stall or die.
  if (dds_write(despawn_writer_.writer.get(), &r) < 0)
    ZS_WARN("despawn request for player %llu timed out", (unsigned long long)player_id);
}

dds::PartitionWriter& ZoneLink::zoneWriter(std::map<int, dds::PartitionWriter>& writers,
                                           dds_entity_t topic, int zone) {
  auto it = writers.find(zone);
  if (it != writers.end()) return it->second;
  auto w = dds::makePartitionWriter(participant_.get(), topic, dds::zonePartition(zone),
                                    input_qos_.get());
  return writers.emplace(zone, std::move(w)).first->second;
}

bool ZoneLink::sendInput(const InputCommand& c) {
  zonesim_dds_PlayerInput in{};
  in.player_id = c.player_id;
  in.avatar_id = c.avatar_id;
  in.seq = c.seq;
  in.move_x = c.move_x;
  in.move_z = c.move_z;
  // A zone that stops reading must not stall or kill the gateway: the input is dropped (the
  // zone applies later seqs in order) and counted.
  return dds_write(zoneWriter(input_writers_, topics_.player_input.get(), c.zone).writer.get(),
                   &in) >= 0;
}

bool ZoneLink::sendTransaction(const TransactionCommand& c) {
  zonesim_dds_PlayerTransaction t{};
  t.player_id = c.player_id;
  t.seq = c.tx.seq;
  t.kind = c.tx.kind;
  t.item = c.tx.item;
  t.amount = c.tx.amount;
  t.counterparty = c.tx.counterparty;
  t.price = c.tx.price;
  t.score = c.tx.score;
  t.decided = c.tx.decided;
  dds_entity_t w =
      zoneWriter(transaction_writers_, topics_.player_transactions.get(), c.zone).writer.get();
  return dds_write(w, &t) >= 0;
}

bool ZoneLink::askLeaderboard(const LeaderboardCommand& c) {
  zonesim_dds_LeaderboardRequest r{};
  r.player_id = c.player_id;
  r.count = c.count;
  dds_entity_t w =
      zoneWriter(leaderboard_writers_, topics_.leaderboard_requests.get(), c.zone).writer.get();
  return dds_write(w, &r) >= 0;
}

std::vector<LeaderboardReplyMsg> ZoneLink::takeLeaderboards() {
  std::vector<LeaderboardReplyMsg> out;
  dds::takeAll<zonesim_dds_LeaderboardReply>(
      leaderboard_reader_.reader.get(), [&](const zonesim_dds_LeaderboardReply& r) {
        LeaderboardReplyMsg m{r.player_id, {}, std::string(r.reason)};
        for (std::uint32_t i = 0; i < r.rows._length; ++i)
          m.rows.push_back({r.rows._buffer[i].player, r.rows._buffer[i].score, r.rows._buffer[i].tick});
        out.push_back(std::move(m));
      });
  return out;
}

std::vector<TransactionOutcomeMsg> ZoneLink::takeOutcomes() {
  // Any epoch's: an outcome says what the database holds, which no restart takes back.
  std::vector<TransactionOutcomeMsg> out;
  dds::takeAll<zonesim_dds_TransactionOutcome>(
      outcome_reader_.reader.get(), [&](const zonesim_dds_TransactionOutcome& o) {
        out.push_back({o.player_id, o.seq, o.status, std::string(o.reason)});
      });
  return out;
}

void ZoneLink::subscribeCell(int cell, int ix, int iz) {
  if (cells_.contains(cell)) return;
  std::string partition = dds::cellPartition(ix, iz);
  CellReaders r;
  r.updates = dds::makePartitionReader(participant_.get(), topics_.cell_updates.get(), partition,
                                       update_qos_.get());
  r.keyframes = dds::makePartitionReader(participant_.get(), topics_.cell_keyframes.get(),
                                         partition, keyframe_qos_.get());
  cells_.emplace(cell, std::move(r));
  ZS_DEBUG("subscribed %s", partition.c_str());
}

void ZoneLink::unsubscribeCell(int cell) {
  cells_.erase(cell);
}

std::vector<zonesim_dds_OwnershipEvent> ZoneLink::takeOwnership() {
  std::vector<zonesim_dds_OwnershipEvent> out;
  dds::takeAll<zonesim_dds_OwnershipEvent>(
      ownership_reader_.reader.get(),
      [&](const zonesim_dds_OwnershipEvent& e) { out.push_back(e); });
  return out;
}

std::size_t ZoneLink::takeCells(WorldCache& cache, ZoneClock& clock, EpochTimeline& timeline,
                                std::int64_t now_ns) {
  std::size_t n = 0;
  for (auto& [cell, r] : cells_) {
    // Keyframes first: a batch of the same tick then applies on top of a complete picture.
    n += dds::takeAll<zonesim_dds_CellKeyframe>(
        r.keyframes.reader.get(), [&](const zonesim_dds_CellKeyframe& k) {
          if (k.cell != cell) return;  // misaddressed
          std::optional<MappedTime> at = timeline.map(k.epoch, k.tick, k.sim_time);
          if (!at) return;  // a zone of a world since restarted
          clock.observe(at->tick, at->sim_time, k.dilation, now_ns);
          cache.applyKeyframe(k, {at->tick, at->sim_time, k.epoch}, now_ns);
        });
    n += dds::takeAll<zonesim_dds_CellUpdateBatch>(
        r.updates.reader.get(), [&](const zonesim_dds_CellUpdateBatch& b) {
          if (b.cell != cell) return;  // misaddressed
          std::optional<MappedTime> at = timeline.map(b.epoch, b.tick, b.sim_time);
          if (!at) return;
          clock.observe(at->tick, at->sim_time, b.dilation, now_ns);
          cache.applyBatch(b, {at->tick, at->sim_time, b.epoch}, now_ns);
        });
  }
  return n;
}

}  // namespace zonesim::gateway
