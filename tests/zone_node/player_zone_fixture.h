#pragma once
// What the player-protocol tests share (players_test.cpp, transactions_test.cpp): a zone's
// store and tallies for PlayerZone, its real DDS link on a private domain, and a participant
// that plays the gateway, with a writer of spawn requests.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "common/scene.h"
#include "idl/dds_entity.h"
#include "idl/dds_qos.h"
#include "idl/topics.h"
#include "support/dds_test_domain.h"
#include "zone_fixture.h"
#include "zone_node/net/gateway_link.h"
#include "zone_node/players.h"
#include "zone_node/tick_profile.h"
#include "zonesim.h"

namespace zonesim::zone {

class PlayerZoneTest : public ::testing::Test {
 protected:
  PlayerZoneTest()
      : scene_(zonesim::testing::npcScene(0)),
        link_(zonesim::testing::privateDdsDomain(), 0, 0),
        gateway_(dds::makeParticipant(zonesim::testing::privateDdsDomain())),
        topics_(dds::makeTopics(gateway_.get())),
        keep_all_(dds::reliableKeepAllQos()),
        spawns_(dds::makePartitionWriter(gateway_.get(), topics_.spawn_requests.get(), "",
                                         keep_all_.get())) {}

  PlayerZone zone() { return {store_, ledger_, ids_, leavers_, counters_, &link_, tick_}; }
  /// Asks the zones, as a gateway session would, for `player`'s avatar at (50, 50).
  void requestSpawn(std::uint64_t player, std::uint64_t session) {
    zonesim_dds_SpawnRequest r{};
    r.player_id = player;
    r.position = {50, 0, 50};
    r.session = session;
    dds::check(dds_write(spawns_.writer.get(), &r), "write SpawnRequest");
  }

  Scene scene_;
  GatewayLink link_;
  EntityStore store_;
  IdSetDigest ledger_;  // created here minus destroyed here
  EntityIdAllocator ids_{0};
  std::vector<Departure> leavers_;
  TickCounters counters_;
  std::uint64_t tick_ = 0;
  dds::Entity gateway_;
  dds::Topics topics_;
  dds::Qos keep_all_;
  dds::PartitionWriter spawns_;
};

}  // namespace zonesim::zone
