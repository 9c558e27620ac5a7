#include "zone_node/net/gateway_link.h"

#include <algorithm>

#include "idl/dds_qos.h"
#include "idl/dds_take.h"
#include "zonesim.h"

namespace zonesim::zone {

namespace {
// Into a topic's bounded string (char[N + 1]): cut to fit, always terminated.
template <std::size_t N>
void copyBounded(std::string_view text, char (&out)[N]) {
  std::size_t n = std::min(text.size(), N - 1);
  std::copy_n(text.data(), n, out);
  out[n] = '\0';
}
}  // namespace

GatewayLink::GatewayLink(int domain, int rank, std::uint32_t epoch)
    : participant_(dds::makeParticipant(domain)),
      topics_(dds::makeTopics(participant_.get())),
      epoch_(epoch) {
  dds::Qos q = dds::reliableKeepAllQos();
  inputs_ = dds::makePartitionReader(participant_.get(), topics_.player_input.get(),
                                     dds::zonePartition(rank), q.get());
  spawns_ = dds::makePartitionReader(participant_.get(), topics_.spawn_requests.get(), "", q.get());
  despawns_ =
      dds::makePartitionReader(participant_.get(), topics_.despawn_requests.get(), "", q.get());
  ownership_ = dds::makePartitionWriter(participant_.get(), topics_.ownership.get(), "", q.get());
  transactions_ = dds::makePartitionReader(participant_.get(), topics_.player_transactions.get(),
                                           dds::zonePartition(rank), q.get());
  outcomes_ =
      dds::makePartitionWriter(participant_.get(), topics_.transaction_outcomes.get(), "", q.get());
  leaderboard_requests_ = dds::makePartitionReader(
      participant_.get(), topics_.leaderboard_requests.get(), dds::zonePartition(rank), q.get());
  leaderboard_replies_ =
      dds::makePartitionWriter(participant_.get(), topics_.leaderboard_replies.get(), "", q.get());
}

std::vector<LeaderboardRequestMsg> GatewayLink::takeLeaderboardRequests() {
  std::vector<LeaderboardRequestMsg> out;
  dds::takeAll<zonesim_dds_LeaderboardRequest>(
      leaderboard_requests_.reader.get(),
      [&](const zonesim_dds_LeaderboardRequest& r) { out.push_back({r.player_id, r.count}); });
  return out;
}

void GatewayLink::publishLeaderboard(std::uint64_t player_id,
                                     std::span<const ledger::LeaderboardRow> rows,
                                     std::string_view reason) {
  zonesim_dds_LeaderboardEntry entries[dds::kLeaderboardRows];
  std::size_t n = std::min(rows.size(), dds::kLeaderboardRows);
  for (std::size_t i = 0; i < n; ++i)
    entries[i] = {rows[i].player, rows[i].score, rows[i].tick};
  zonesim_dds_LeaderboardReply r{};
  r.player_id = player_id;
  r.rows._buffer = entries;
  r.rows._length = r.rows._maximum = std::uint32_t(n);
  r.rows._release = false;
  copyBounded(reason, r.reason);
  if (dds_write(leaderboard_replies_.writer.get(), &r) < 0) ++write_failures_;
}

std::vector<PlayerTransactionMsg> GatewayLink::takeTransactions() {
  std::vector<PlayerTransactionMsg> out;
  dds::takeAll<zonesim_dds_PlayerTransaction>(
      transactions_.reader.get(), [&](const zonesim_dds_PlayerTransaction& t) {
        out.push_back(
            {t.player_id, t.seq, t.kind, t.item, t.amount, t.counterparty, t.price, t.score,
             t.decided});
      });
  return out;
}

void GatewayLink::publishOutcome(std::uint64_t player_id, std::uint32_t seq, std::uint8_t status,
                                 std::string_view reason) {
  zonesim_dds_TransactionOutcome o{};
  o.player_id = player_id;
  o.seq = seq;
  o.status = status;
  copyBounded(reason, o.reason);
  o.epoch = epoch_;
  // As for announcements: a gateway that stopped reading must not stall the zone. The client
  // asks again, and the zone answers again.
  if (dds_write(outcomes_.writer.get(), &o) < 0) ++write_failures_;
}

std::vector<PlayerInputMsg> GatewayLink::takeInputs() {
  std::vector<PlayerInputMsg> out;
  dds::takeAll<zonesim_dds_PlayerInput>(inputs_.reader.get(),
                                        [&](const zonesim_dds_PlayerInput& s) {
                                          out.push_back({s.player_id, s.seq, s.move_x, s.move_z});
                                        });
  return out;
}

std::vector<SpawnRequestMsg> GatewayLink::takeSpawnRequests() {
  std::vector<SpawnRequestMsg> out;
  dds::takeAll<zonesim_dds_SpawnRequest>(
      spawns_.reader.get(), [&](const zonesim_dds_SpawnRequest& s) {
        out.push_back(
            {s.player_id, double(s.position.x), double(s.position.z), s.kind, s.session});
      });
  return out;
}

std::vector<DespawnRequestMsg> GatewayLink::takeDespawnRequests() {
  std::vector<DespawnRequestMsg> out;
  dds::takeAll<zonesim_dds_DespawnRequest>(
      despawns_.reader.get(),
      [&](const zonesim_dds_DespawnRequest& s) { out.push_back({s.player_id, s.session}); });
  return out;
}

void GatewayLink::announce(const OwnershipMsg& m) {
  zonesim_dds_OwnershipEvent s{};
  s.player_id = m.player_id;
  s.avatar_id = m.avatar_id;
  s.from_zone = m.from_zone;
  s.to_zone = m.to_zone;
  s.tick = m.tick;
  s.last_input_seq = m.last_input_seq;
  s.epoch = epoch_;
  // A gateway that stopped reading fills a KEEP_ALL writer and the write times out: the zone
  // goes on (inputs still reach the avatar through forwarding) and counts it.
  if (dds_write(ownership_.writer.get(), &s) < 0) ++write_failures_;
}

}  // namespace zonesim::zone
