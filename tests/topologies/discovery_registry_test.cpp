#include "topologies/discovery_registry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace zonesim::topo {
namespace {

Registration entry(std::uint32_t player, Role role, std::uint16_t port) {
  return {player, role, gateway::Endpoint::loopback(port)};
}

TEST(DiscoveryRegistry, ListsRegisteredPlayersInPlayerOrder) {
  DiscoveryRegistry reg;
  reg.add(entry(3, Role::Peer, 4003), 0, 5);
  reg.add(entry(1, Role::Host, 4001), 0, 5);
  reg.add(entry(2, Role::Client, 4002), 0, 5);
  std::vector<Registration> l = reg.list(1);
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(l[0].player, 1u);
  EXPECT_EQ(l[0].role, Role::Host);
  EXPECT_EQ(l[0].address, gateway::Endpoint::loopback(4001));
  EXPECT_EQ(l[1].player, 2u);
  EXPECT_EQ(l[2].player, 3u);
}

TEST(DiscoveryRegistry, ReRegisteringReplacesAndRefreshes) {
  DiscoveryRegistry reg;
  reg.add(entry(7, Role::Peer, 4000), 0, 5);
  reg.add(entry(7, Role::Peer, 4100), 4, 5);  // moved port, refreshed until 9
  std::vector<Registration> l = reg.list(8);
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].address.port, 4100);
}

TEST(DiscoveryRegistry, ExpiredEntriesLeaveTheList) {
  DiscoveryRegistry reg;
  reg.add(entry(1, Role::Host, 4001), 0, 2);
  reg.add(entry(2, Role::Client, 4002), 0, 10);
  EXPECT_EQ(reg.list(1.999).size(), 2u);
  std::vector<Registration> l = reg.list(2.0);  // alive until, not including, now + ttl
  ASSERT_EQ(l.size(), 1u);
  EXPECT_EQ(l[0].player, 2u);
  EXPECT_EQ(reg.size(), 1u);  // forgotten, not only hidden
  EXPECT_TRUE(reg.list(10).empty());
}

TEST(DiscoveryRegistry, RefusesATimeToLiveOutOfRange) {
  DiscoveryRegistry reg;
  for (double ttl : {0.0, -1.0, kMaxTtlSeconds + 1, std::nan("")}) {
    try {
      reg.add(entry(1, Role::Peer, 4000), 0, ttl);
      FAIL() << "ttl " << ttl << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("time to live"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(reg.size(), 0u);
}

}  // namespace
}  // namespace zonesim::topo
