#include "topologies/node_config.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace zonesim::topo {
namespace {

TEST(NodeConfig, CheatListsParseAndName) {
  EXPECT_EQ(parseCheats("none").names(), "none");
  Cheats c = parseCheats("hit,teleport");
  EXPECT_TRUE(c.hit);
  EXPECT_TRUE(c.teleport);
  EXPECT_FALSE(c.speed);
  EXPECT_EQ(c.names(), "teleport,hit");
  EXPECT_FALSE(c.peerOnly());
  Cheats peer = parseCheats("equivocate,vote");
  EXPECT_TRUE(peer.vote && peer.equivocate && peer.peerOnly());
  EXPECT_EQ(peer.names(), "vote,equivocate");
}

TEST(NodeConfig, AnUnknownCheatOrRoleIsNamed) {
  try {
    parseCheats("speed,fly");
    FAIL() << "fly accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "cheat 'fly' is not one of none, teleport, speed, hit, vote, equivocate");
  }
  EXPECT_THROW(parseCheats("speed,"), std::invalid_argument);
  try {
    parseRole("server");
    FAIL() << "server accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "role 'server' is not one of host, client, peer");
  }
}

}  // namespace
}  // namespace zonesim::topo
