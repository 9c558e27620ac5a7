// client_stub's fleet against a real Gateway and a test zone on a private DDS domain: every
// player is welcomed, sees entities, and the summary and metrics come out in their shape.
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "../gateway/gateway_fixture.h"
#include "clients/fleet.h"
#include "clients/kind_mix.h"
#include "common/timer.h"
#include "gateway/gateway.h"

namespace zonesim::clients {
namespace {

// The zone: one avatar per spawn request, every avatar published in its cell each tick, until
// done is set. Returns the requests, by avatar id.
std::map<std::uint64_t, zonesim_dds_SpawnRequest> runZone(testing::ZoneEmulator& zone,
                                                          const std::atomic<bool>& done) {
  std::map<std::uint64_t, zonesim_dds_SpawnRequest> avatars;
  std::uint64_t tick = 0, next_avatar = 0x1000000000001ULL;
  while (!done) {
    for (const auto& r : zone.takeSpawnRequests()) {
      avatars[next_avatar] = r;
      zone.publishOwnership(r.player_id, next_avatar++, -1, 0, tick, 0);
    }
    ++tick;
    for (const auto& [id, r] : avatars)
      zone.publishBatch(r.position.x, r.position.z, 0, tick, {},
                        {testing::entity(id, 1, r.position.x, r.position.z, 0.5f, 0)});
    zone.takeInputs(0);
    std::this_thread::sleep_for(std::chrono::milliseconds(33));  // the zone's tick pacing
  }
  return avatars;
}

void checkSummary(const nlohmann::json& summary, int players) {
  EXPECT_EQ(summary["players"], players);
  EXPECT_GT(summary["duration_s"].get<double>(), 2.0);
  ASSERT_EQ(summary["clients"].size(), std::size_t(players));
  for (const auto& c : summary["clients"]) {
    EXPECT_NE(c["player_id"].get<std::uint64_t>(), 0u);
    EXPECT_NE(c["avatar_id"].get<std::uint64_t>(), 0u);
    EXPECT_GT(c["bytes_in_per_s"].get<double>(), 0);
    EXPECT_GT(c["bytes_out_per_s"].get<double>(), 0);
    EXPECT_GT(c["updates_per_s"].get<double>(), 0);
    EXPECT_GE(c["visible_entities"].get<int>(), 1);
    EXPECT_GT(c["rtt_ms_p50"].get<double>(), 0);
    EXPECT_EQ(c["dropped"], 0);
  }
  EXPECT_TRUE(summary["totals"].contains("handoffs"));
  EXPECT_EQ(summary["totals"]["welcomed"], players);
  // The fleet's own cost: its thread's CPU, part of the process's (the gateway's too here).
  double cpu_s = summary["fleet_cpu_s"].get<double>();
  EXPECT_GT(cpu_s, 0);
  EXPECT_GE(summary["fleet_process_cpu_s"].get<double>(), cpu_s - 1e-3);
  EXPECT_NEAR(summary["fleet_cpu_us_per_player_s"].get<double>(),
              cpu_s * 1e6 / (players * summary["duration_s"].get<double>()), 1e-6);
  EXPECT_GT(summary["fleet_wakeups_per_s"].get<double>(), 0);
}

// A real gateway and the test zone on a private DDS domain; play() runs a fleet against them
// until its duration ends.
class FleetLoopback : public ::testing::Test {
 protected:
  void open(const Scene& scene) {
    scene_ = scene;
    gateway::GatewayConfig gcfg;
    gcfg.scene = scene;
    gcfg.dds_domain = domain_;
    gcfg.gateway_id = testing::privateGatewayId();
    gcfg.expected_zones = 1;
    gw_ = std::make_unique<gateway::Gateway>(gcfg);
    zone_ = std::make_unique<testing::ZoneEmulator>(domain_, scene, gcfg.gateway_id);
  }
  // A fleet of `players` for 2.5 s at this gateway.
  FleetConfig fleetConfig(int players) const {
    FleetConfig f;
    f.player.gateway = gateway::Endpoint::loopback(gw_->port());
    f.player.world = scene_.world;
    f.players = players;
    f.duration_s = 2.5;
    return f;
  }
  // Runs gateway, fleet and zone until the fleet is done; the zone's spawn requests by avatar.
  std::map<std::uint64_t, zonesim_dds_SpawnRequest> play(ClientFleet& fleet) {
    std::atomic<bool> stop_gateway{false}, stop_fleet{false}, fleet_done{false};
    std::thread gateway_thread([&] { gw_->run(stop_gateway); });
    std::thread fleet_thread([&] {
      fleet.run(stop_fleet);
      fleet_done = true;
    });
    std::map<std::uint64_t, zonesim_dds_SpawnRequest> requests = runZone(*zone_, fleet_done);
    fleet_thread.join();
    stop_gateway = true;
    gateway_thread.join();
    return requests;
  }

  int domain_ = testing::privateDdsDomain();
  Scene scene_;
  std::unique_ptr<gateway::Gateway> gw_;
  std::unique_ptr<testing::ZoneEmulator> zone_;
};

TEST_F(FleetLoopback, PlayersAreWelcomedAndSeeTheWorld) {
  open(testing::smallScene());
  std::string metrics = ::testing::TempDir() + "/clients_" + std::to_string(domain_) + ".jsonl";
  FleetConfig fcfg = fleetConfig(3);
  fcfg.metrics_path = metrics;
  ClientFleet fleet(fcfg);
  play(fleet);

  EXPECT_EQ(fleet.welcomed(), 3);
  checkSummary(nlohmann::json::parse(fleet.summaryJson()), 3);
  std::ifstream lines(metrics);
  std::string line;
  int n = 0;
  for (; std::getline(lines, line); ++n)
    EXPECT_TRUE(nlohmann::json::parse(line).contains("bytes_in_per_s"));
  EXPECT_GE(n, 2);
  EXPECT_GE(gw_->counters().inputs_forwarded, 1u);
}

// With every datagram held 20 ms each way, what the players get comes off their downlinks only
// when the loop wakes for it: the Welcome, the states and the Pongs all arrive, and no round
// trip is shorter than the two delays.
TEST_F(FleetLoopback, HeldDatagramsArriveThroughTheLoop) {
  open(testing::smallScene());
  constexpr double kDelayMs = 20;
  FleetConfig fcfg = fleetConfig(3);
  fcfg.player.impairment.out.delay_ms = kDelayMs;
  fcfg.player.impairment.in.delay_ms = kDelayMs;
  ClientFleet fleet(fcfg);
  play(fleet);

  EXPECT_EQ(fleet.welcomed(), 3);
  nlohmann::json summary = nlohmann::json::parse(fleet.summaryJson());
  checkSummary(summary, 3);
  for (const auto& c : summary["clients"])
    EXPECT_GE(c["rtt_ms_p50"].get<double>(), 2 * kDelayMs) << "each way held its delay";
  for (const auto& p : fleet.players()) {
    gateway::ImpairmentCounters c = p->impairment().counters();
    EXPECT_GT(c.in.delivered, 0u);
    EXPECT_GT(c.out.delivered, 0u);
  }
}

TEST_F(FleetLoopback, KindsAreMixedByTheSharesAndReportedPerKind) {
  Scene scene = testing::smallScene();
  scene.clients.kinds = {{PlayerKindId::Walker, 5, 40, 0, 0.5},
                         {PlayerKindId::Flyer, 20, 60, 10, 0.5}};
  open(scene);
  FleetConfig fcfg = fleetConfig(4);
  fcfg.kinds = fleetKinds(scene.clients);
  ClientFleet fleet(fcfg);
  std::map<std::uint64_t, zonesim_dds_SpawnRequest> requests = play(fleet);

  ASSERT_EQ(fleet.welcomed(), 4);
  int flyers_asked = 0;
  for (const auto& [avatar, r] : requests) flyers_asked += r.kind == 2 ? 1 : 0;
  EXPECT_EQ(flyers_asked, 2) << "the zones were asked for two flyers";
  nlohmann::json summary = nlohmann::json::parse(fleet.summaryJson());
  int flyers_listed = 0;
  for (const auto& c : summary["clients"]) flyers_listed += c["kind"] == "flyer" ? 1 : 0;
  EXPECT_EQ(flyers_listed, 2);
  const nlohmann::json& kinds = summary["kinds"];
  ASSERT_EQ(kinds.size(), 2u) << kinds;
  for (const char* k : {"walker", "flyer"}) {
    EXPECT_EQ(kinds[k]["players"], 2) << k;
    EXPECT_GT(kinds[k]["kbps_in_p50"].get<double>(), 0) << k;
    EXPECT_GE(kinds[k]["kbps_in_max"].get<double>(), kinds[k]["kbps_in_p50"].get<double>());
    EXPECT_GE(kinds[k]["visible_entities_mean"].get<double>(), 1) << "its own avatar at least";
    EXPECT_TRUE(kinds[k].contains("dr_error_m_max"));
  }
  nlohmann::json g = nlohmann::json::parse(gw_->summaryJson());
  EXPECT_EQ(g["sessions_by_kind"]["walker"], 2);
  EXPECT_EQ(g["sessions_by_kind"]["flyer"], 2);
  EXPECT_EQ(g["sessions_by_kind"]["rider"], 0);
}

}  // namespace
}  // namespace zonesim::clients
