#pragma once
// Shared by the gateway and clients tests: a small scene, a private DDS domain per test process,
// and a zone emulator made of real DDS readers and writers that plays the zones' side of the
// contract (answers SpawnRequests with OwnershipEvents, publishes CellUpdateBatches, reads
// PlayerInputs).

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "common/interest_grid.h"
#include "common/scene.h"
#include "idl/dds_entity.h"
#include "idl/dds_qos.h"
#include "idl/topics.h"
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

namespace detail {
// Cyclone's default port mapping: domain d uses UDP ports 7400 + 250 d + [0, 250), d <= 232.
constexpr int kDdsPortBase = 7400, kDdsDomainGain = 250, kMaxDdsDomain = 232;

// The range bind(port 0) draws from: every UDP socket of the gateway and of the sim players.
inline std::pair<int, int> ephemeralPorts() {
  int lo = 32768, hi = 60999;  // Linux's default
  std::ifstream f("/proc/sys/net/ipv4/ip_local_port_range");
  if (!(f >> lo >> hi)) return {32768, 60999};
  return {lo, hi};
}

// Domains none of whose ports can be handed out as ephemeral ports. With unicast discovery
// (deploy/cyclonedds.xml) every participant sends its SPDP announcements to 127.0.0.1 at the
// discovery port of all 61 participant indices of its domain, whether anything listens there or
// not: a test socket that drew one of those ports receives RTPS datagrams, which the gateway and
// the clients rightly count as drops. Domain 0 is left to hand-started runs.
inline std::vector<int> domainsClearOfEphemeralPorts() {
  auto [lo, hi] = ephemeralPorts();
  std::vector<int> clear;
  for (int d = 1; d <= kMaxDdsDomain; ++d) {
    int first = kDdsPortBase + kDdsDomainGain * d, last = first + kDdsDomainGain - 1;
    if (last < lo || first > hi) clear.push_back(d);
  }
  return clear;
}

// Holds an advisory lock on domain d for the life of the process; false if another holds it.
inline bool lockDomain(int d) {
  std::error_code ec;
  auto dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  auto path = dir / ("zonesim_test_dds_domain_" + std::to_string(d) + ".lock");
  int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return true;  // fd stays open: the lock with it
  ::close(fd);
  return false;
}

inline int pickDdsDomain() {
  std::vector<int> domains = domainsClearOfEphemeralPorts();
  // An ephemeral range that spans every domain: isolation by port is impossible, take any.
  for (int d = 1; domains.empty() && d <= kMaxDdsDomain; ++d) domains.push_back(d);
  auto t = std::chrono::steady_clock::now().time_since_epoch().count();
  std::size_t start = std::size_t((std::uint64_t(getpid()) * 7919 + std::uint64_t(t)) %
                                  std::uint64_t(domains.size()));
  // Two test processes on one domain see each other's samples (and a spawn writer may count
  // the other test's zone as matched): the lock keeps the gateway and clients tests apart.
  for (std::size_t i = 0; i < domains.size(); ++i) {
    int d = domains[(start + i) % domains.size()];
    if (lockDomain(d)) return d;
  }
  return domains[start];
}
}  // namespace detail

/// Points Cyclone at the loopback config and returns a domain that no other gateway or clients
/// test process uses at the same time, whose ports none of the tests' UDP sockets can draw.
inline int privateDdsDomain() {
  setenv("CYCLONEDDS_URI", "file://" ZONESIM_CYCLONEDDS_XML, 1);
  static const int domain = detail::pickDdsDomain();
  return domain;
}

/// A gateway id unlikely to be shared with a test in another process that drew the same domain;
/// the zone emulator answers only its players.
inline std::uint32_t privateGatewayId() {
  auto t = std::chrono::steady_clock::now().time_since_epoch().count();
  return 1 +
         std::uint32_t((std::uint64_t(getpid()) * 2654435761u + std::uint64_t(t)) % 0xfffffff0u);
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
    std::erase_if(all, [&](const auto& r) { return (r.player_id >> 32) != gateway_id_; });
    return all;
  }

  /// Announces that `to_zone` owns the player's avatar.
  void publishOwnership(std::uint64_t player, std::uint64_t avatar, int from_zone, int to_zone,
                        std::uint64_t tick, std::uint32_t last_seq) {
    zonesim_dds_OwnershipEvent e{player, avatar, from_zone, to_zone, tick, last_seq};
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
    void* samples[16];
    dds_sample_info_t infos[16];
    for (;;) {
      std::fill(std::begin(samples), std::end(samples), nullptr);
      int n = dds_take(reader, samples, infos, 16, 16);
      for (int i = 0; i < n; ++i)
        if (infos[i].valid_data) out.push_back(*static_cast<T*>(samples[i]));
      if (n > 0) dds_return_loan(reader, samples, n);
      if (n < 16) return out;
    }
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
