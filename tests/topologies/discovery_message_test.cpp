#include "topologies/discovery_message.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace zonesim::topo {
namespace {

// The message of the std::invalid_argument that parsing text throws ("" if none).
template <typename Parse>
std::string errorOf(Parse parse) {
  try {
    parse();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(DiscoveryMessage, RegisterRoundTrips) {
  RegisterRequest r{{12, Role::Host, gateway::Endpoint{0x7f000001, 5555}}, 2.5};
  std::string text = formatRequest(r);
  EXPECT_EQ(text, "register 12 host 127.0.0.1:5555 2.5");
  auto back = std::get<RegisterRequest>(parseRequest(text));
  EXPECT_EQ(back.registration.player, 12u);
  EXPECT_EQ(back.registration.role, Role::Host);
  EXPECT_EQ(back.registration.address, r.registration.address);
  EXPECT_DOUBLE_EQ(back.ttl_s, 2.5);
  EXPECT_TRUE(std::holds_alternative<ListRequest>(parseRequest("list")));
}

TEST(DiscoveryMessage, PeersRoundTrip) {
  std::vector<Registration> in{{0, Role::Peer, gateway::Endpoint{0x7f000001, 4000}},
                               {5, Role::Client, gateway::Endpoint{0x0a000002, 4001}}};
  std::vector<Registration> out = parsePeers(formatPeers(in));
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[1].player, 5u);
  EXPECT_EQ(out[1].role, Role::Client);
  EXPECT_EQ(out[1].address.str(), "10.0.0.2:4001");
  EXPECT_TRUE(parsePeers("peers 0").empty());
}

TEST(DiscoveryMessage, BadRequestsNameWhatIsWrong) {
  auto req = [](const char* text) { return errorOf([&] { parseRequest(text); }); };
  EXPECT_NE(req("").find("empty request"), std::string::npos);
  EXPECT_NE(req("hello").find("unknown request 'hello'"), std::string::npos);
  EXPECT_NE(req("list 3").find("'list' takes no arguments"), std::string::npos);
  EXPECT_NE(req("register 1 peer 127.0.0.1:4000").find("got 3 arguments"), std::string::npos);
  EXPECT_NE(req("register x peer 127.0.0.1:4000 5").find("player 'x'"), std::string::npos);
  EXPECT_NE(
      req("register 1 king 127.0.0.1:4000 5").find("role 'king' is not one of host, client, peer"),
      std::string::npos);
  EXPECT_NE(req("register 1 peer localhost:4000 5").find("'localhost' is not a dotted IPv4"),
            std::string::npos);
  EXPECT_NE(req("register 1 peer 127.0.0.1 5").find("has no ':PORT'"), std::string::npos);
  EXPECT_NE(req("register 1 peer 127.0.0.1:70000 5").find("port '70000'"), std::string::npos);
  EXPECT_NE(req("register 1 peer 127.0.0.1:0 5").find("port 0"), std::string::npos);
  EXPECT_NE(req("register 1 peer 127.0.0.1:4000 soon").find("ttl 'soon'"), std::string::npos);
  EXPECT_NE(req("register 1 peer 127.0.0.1:4000 0").find("ttl '0' is not in"), std::string::npos);
  EXPECT_NE(req("register 1 peer 127.0.0.1:4000 nan").find("ttl 'nan'"), std::string::npos);
  std::string huge(kMaxDiscoveryBytes + 1, 'x');
  EXPECT_NE(req(huge.c_str()).find("longer than"), std::string::npos);
}

TEST(DiscoveryMessage, BadRepliesNameWhatIsWrong) {
  auto peers = [](const char* text) { return errorOf([&] { parsePeers(text); }); };
  EXPECT_NE(peers("error role 'x' is bad").find("discovery service refused: role 'x' is bad"),
            std::string::npos);
  EXPECT_NE(peers("ok").find("does not start with 'peers N'"), std::string::npos);
  EXPECT_NE(peers("peers 2\n1 peer 127.0.0.1:4000").find("says 2 peers but lists 1"),
            std::string::npos);
  EXPECT_NE(peers("peers 1\n1 peer").find("peer line 1"), std::string::npos);
}

}  // namespace
}  // namespace zonesim::topo
