// A lobby, two gateways with the cluster's key and their zone emulators on a private DDS domain,
// and a fleet that logs in through the lobby: the gateways report their load, the lobby spreads
// the players over both, each player is welcomed by the gateway it was given, and a token
// replayed from another socket, or sent to the other gateway, is refused and counted.
#include <gtest/gtest.h>

#include <atomic>
#include <map>
#include <thread>

#include "../gateway/gateway_fixture.h"
#include "clients/fleet.h"
#include "gateway/gateway.h"
#include "lobby/lobby.h"

namespace zonesim::lobby {
namespace {

auth::AuthKey clusterKey() {
  std::vector<std::uint8_t> b(32);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::uint8_t(0x40 + 3 * i);
  return auth::AuthKey(b, "test key");
}

// One avatar per spawn request of the zone's gateway, each published in its cell every tick.
void runZones(std::vector<testing::ZoneEmulator*> zones, const std::atomic<bool>& done) {
  std::map<std::uint64_t, zonesim_dds_SpawnRequest> avatars;
  std::uint64_t tick = 0, next_avatar = 0x1000000000001ULL;
  while (!done) {
    for (testing::ZoneEmulator* zone : zones) {
      for (const auto& r : zone->takeSpawnRequests()) {
        avatars[next_avatar] = r;
        zone->publishOwnership(r.player_id, next_avatar++, -1, 0, tick, 0);
      }
      zone->takeInputs(0);
    }
    ++tick;
    for (const auto& [id, r] : avatars)
      zones[0]->publishBatch(r.position.x, r.position.z, 0, tick, {},
                             {testing::entity(id, 1, r.position.x, r.position.z, 0.5f, 0)});
    std::this_thread::sleep_for(std::chrono::milliseconds(33));  // the zone's tick pacing
  }
}

TEST(LobbyLoopback, PlayersLogInAndSpreadOverTheGateways) {
  int domain = testing::privateDdsDomain();
  Scene scene = testing::smallScene();
  std::uint32_t first_id = testing::privateGatewayId();
  std::uint32_t ids[2] = {first_id, first_id % 0xfffe + 1};
  std::vector<std::unique_ptr<gateway::Gateway>> gateways;
  std::vector<std::unique_ptr<testing::ZoneEmulator>> zones;
  for (std::uint32_t id : ids) {
    gateway::GatewayConfig g;
    g.scene = scene;
    g.dds_domain = domain;
    g.gateway_id = id;
    g.expected_zones = 1;
    g.auth_key = clusterKey();
    gateways.push_back(std::make_unique<gateway::Gateway>(g));
    zones.push_back(std::make_unique<testing::ZoneEmulator>(domain, scene, id));
  }
  LobbyConfig lcfg;
  lcfg.dds_domain = domain;
  lcfg.login.expect_gateways = 2;  // so the first logins cannot beat the second report
  Lobby lobby(lcfg, clusterKey());

  std::atomic<bool> stop_servers{false}, stop_fleet{false}, fleet_done{false};
  std::vector<std::thread> servers;
  for (auto& g : gateways) servers.emplace_back([&, gw = g.get()] { gw->run(stop_servers); });
  servers.emplace_back([&] { lobby.run(stop_servers); });

  clients::FleetConfig fcfg;
  fcfg.player.world = scene.world;
  fcfg.players = 4;
  fcfg.duration_s = 2.0;
  fcfg.lobby = clients::LobbyLoginSettings{lobby.local()};
  // Logs in here: the lobby retries its refusals until both gateways have reported.
  clients::ClientFleet fleet(fcfg, stop_fleet);
  ASSERT_EQ(fleet.tickets().size(), 4u);
  std::map<std::uint16_t, int> per_gateway;
  for (const auto& t : fleet.tickets()) ++per_gateway[t.gateway_id];

  // Player 0's token, replayed from another socket to its gateway, and sent to the other one.
  const clients::LoginTicket& t0 = fleet.tickets()[0];
  gateway::UdpSocket thief(gateway::Endpoint::any(0));
  thief.sendTo(t0.gateway, gateway::encodeHello(99, "thief", t0.connect_token));
  const clients::LoginTicket* other = nullptr;
  for (const auto& t : fleet.tickets())
    if (t.gateway_id != t0.gateway_id) other = &t;
  ASSERT_NE(other, nullptr);
  thief.sendTo(other->gateway, gateway::encodeHello(98, "thief", t0.connect_token));

  std::thread fleet_thread([&] {
    fleet.run(stop_fleet);
    fleet_done = true;
  });
  runZones({zones[0].get(), zones[1].get()}, fleet_done);
  fleet_thread.join();
  stop_servers = true;
  for (auto& t : servers) t.join();

  EXPECT_EQ(fleet.welcomed(), 4);
  // Four logins at once, before either gateway reported a session: two each.
  EXPECT_EQ(per_gateway[std::uint16_t(ids[0])], 2);
  EXPECT_EQ(per_gateway[std::uint16_t(ids[1])], 2);
  std::uint64_t wrong_address = 0, wrong_gateway = 0;
  for (auto& g : gateways) {
    wrong_address += g->drops()[gateway::DropReason::TokenWrongAddress];
    wrong_gateway += g->drops()[gateway::DropReason::TokenWrongGateway];
    EXPECT_EQ(g->drops()[gateway::DropReason::TokenForged], 0u);
    EXPECT_EQ(g->drops()[gateway::DropReason::TokenMissing], 0u);
    EXPECT_EQ(g->counters().sessions_opened, 2u);
    EXPECT_EQ(g->drops().total(), 1u) << "the one refused token";
  }
  EXPECT_EQ(wrong_address, 1u);
  EXPECT_EQ(wrong_gateway, 1u);
  EXPECT_EQ(lobby.service().counters().granted, 4u);
  EXPECT_EQ(lobby.service().drops().total(), 0u);
  for (std::size_t i = 0; i < fleet.players().size(); ++i)
    EXPECT_EQ(fleet.players()[i]->playerId(), fleet.tickets()[i].player_id);
}

}  // namespace
}  // namespace zonesim::lobby
