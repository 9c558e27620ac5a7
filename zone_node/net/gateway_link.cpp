#include "zone_node/net/gateway_link.h"

#include "idl/dds_qos.h"
#include "idl/dds_take.h"
#include "zonesim.h"

namespace zonesim::zone {

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
