#pragma once
// Shared by the gateway and clients tests: a small scene, a private DDS domain per test process,
// and a zone emulator made of real DDS readers and writers that plays the zones' side of the
// contract (answers SpawnRequests with OwnershipEvents, publishes CellUpdateBatches, reads
// PlayerInputs).

#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/interest_grid.h"
#include "common/scene.h"
#include "idl/dds_entity.h"
#include "idl/dds_qos.h"
#include "idl/dds_take.h"
#include "idl/topics.h"
#include "support/dds_test_domain.h"
#include "zonesim.h"

namespace zonesim::testing {

/// A 100 m square world, one zone, 25 m cells, 30 Hz.
inline Scene smallScene() {
  Scene s;
  s.name = "test";
  s.world = {{0, 0, 0}, {100, 20, 100}};
  s.tick_rate = 30;
  s.dt = 1.0 / 30;
  s.interest_cell_size = 25;
  s.clients.nimbus = 40;
  s.clients.speed = 5;
  return s;
}

/// A gateway id unlikely to be shared with a test in another process that drew the same domain;
/// the zone emulator answers only its players.
inline std::uint32_t privateGatewayId() {
  auto t = std::chrono::steady_clock::now().time_since_epoch().count();
  return 1 + std::uint32_t((std::uint64_t(getpid()) * 2654435761u + std::uint64_t(t)) % 0xfffeu);
}

/// An entity state for DDS samples.
inline zonesim_dds_EntityUpdate entity(std::uint64_t id, std::uint8_t kind, float x, float z,
                                       float vx = 0, float vz = 0) {
  zonesim_dds_EntityUpdate e{};
  e.id = id;
  e.kind = kind;
  e.pos = {x, 0, z};
  e.vel = {vx, 0, vz};
  e.rot = {0, 0, 0, 1};
  e.model = 1;  // first order, fixed orientation
  return e;
}

/// The zones' side of the DDS contract, for one test.
class ZoneEmulator {
 public:
  /// Serves the players of gateway_id on the domain.
  ZoneEmulator(int domain, const Scene& scene, std::uint32_t gateway_id)
      : gateway_id_(gateway_id),
        grid_(scene.world, scene.interest_cell_size),
        participant_(dds::makeParticipant(domain)),
        topics_(dds::makeTopics(participant_.get())),
        keep_all_(dds::reliableKeepAllQos()),
        update_qos_(dds::cellUpdateQos()) {
    spawn_reader_ = dds::makePartitionReader(participant_.get(), topics_.spawn_requests.get(), "",
                                             keep_all_.get());
    ownership_writer_ =
        dds::makePartitionWriter(participant_.get(), topics_.ownership.get(), "", keep_all_.get());
  }

  /// Takes pending spawn requests of our gateway's players.
  std::vector<zonesim_dds_SpawnRequest> takeSpawnRequests() {
    auto all = take<zonesim_dds_SpawnRequest>(spawn_reader_.reader.get());
    std::erase_if(all,
                  [&](const auto& r) { return ((r.player_id >> 32) & 0xFFFF) != gateway_id_; });
    return all;
  }

  /// Announces that `to_zone` owns the player's avatar, in cluster epoch `epoch`.
  void publishOwnership(std::uint64_t player, std::uint64_t avatar, int from_zone, int to_zone,
                        std::uint64_t tick, std::uint32_t last_seq, std::uint32_t epoch = 0) {
    zonesim_dds_OwnershipEvent e{player, avatar, from_zone, to_zone, tick, last_seq, epoch};
    dds::check(dds_write(ownership_writer_.writer.get(), &e), "write OwnershipEvent");
  }

  /// Publishes one batch for the cell containing (x, z) from `zone`.
  void publishBatch(double x, double z, int zone, std::uint64_t tick,
                    std::vector<zonesim_dds_EntityUpdate> enters,
                    std::vector<zonesim_dds_EntityUpdate> updates) {
    int cell = grid_.cellOf(x, z);
    auto it = cell_writers_.find(cell);
    if (it == cell_writers_.end()) {
      auto w = dds::makePartitionWriter(
          participant_.get(), topics_.cell_updates.get(),
          dds::cellPartition(grid_.columnOfCell(cell), grid_.rowOfCell(cell)), update_qos_.get());
      it = cell_writers_.emplace(cell, std::move(w)).first;
    }
    zonesim_dds_CellUpdateBatch b{};
    b.cell = cell;
    b.zone = zone;
    b.tick = tick;
    b.sim_time = double(tick) / 30.0;
    b.enters = {std::uint32_t(enters.size()), std::uint32_t(enters.size()), enters.data(), false};
    b.updates = {std::uint32_t(updates.size()), std::uint32_t(updates.size()), updates.data(),
                 false};
    dds::check(dds_write(it->second.writer.get(), &b), "write CellUpdateBatch");
  }

  /// Takes inputs that arrived on zone partition z.<zone>.
  std::vector<zonesim_dds_PlayerInput> takeInputs(int zone) {
    auto it = input_readers_.find(zone);
    if (it == input_readers_.end()) {
      auto r = dds::makePartitionReader(participant_.get(), topics_.player_input.get(),
                                        dds::zonePartition(zone), keep_all_.get());
      it = input_readers_.emplace(zone, std::move(r)).first;
    }
    return take<zonesim_dds_PlayerInput>(it->second.reader.get());
  }

 private:
  template <typename T>
  static std::vector<T> take(dds_entity_t reader) {
    std::vector<T> out;
    dds::takeAll<T>(reader, [&](const T& sample) { out.push_back(sample); });
    return out;
  }

  std::uint32_t gateway_id_;
  InterestGrid grid_;
  dds::Entity participant_;
  dds::Topics topics_;
  dds::Qos keep_all_, update_qos_;
  dds::PartitionReader spawn_reader_;
  dds::PartitionWriter ownership_writer_;
  std::map<int, dds::PartitionWriter> cell_writers_;
  std::map<int, dds::PartitionReader> input_readers_;
};

}  // namespace zonesim::testing
