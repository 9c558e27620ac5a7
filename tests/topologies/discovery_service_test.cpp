#include "topologies/discovery_service.h"

#include <gtest/gtest.h>

#include <string_view>

#include "topologies/discovery_message.h"

namespace zonesim::topo {
namespace {

std::span<const std::uint8_t> bytes(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

TEST(DiscoveryService, AnswersRegisterListAndExpiry) {
  DiscoveryService service(gateway::Endpoint::loopback(0));
  EXPECT_EQ(service.answer(bytes("register 0 host 127.0.0.1:4000 2"), 0), "ok");
  EXPECT_EQ(service.answer(bytes("register 1 client 127.0.0.1:4001 10"), 0), "ok");
  EXPECT_EQ(parsePeers(service.answer(bytes("list"), 1)).size(), 2u);
  std::vector<Registration> later = parsePeers(service.answer(bytes("list"), 3));
  ASSERT_EQ(later.size(), 1u);  // the host did not refresh
  EXPECT_EQ(later[0].player, 1u);
  EXPECT_EQ(service.counters().registers, 2u);
  EXPECT_EQ(service.counters().lists, 2u);
}

TEST(DiscoveryService, BadInputGetsAnErrorReplyAndHarmsNothing) {
  DiscoveryService service(gateway::Endpoint::loopback(0));
  std::string reply = service.answer(bytes("register 1 wizard 127.0.0.1:4001 10"), 0);
  EXPECT_EQ(reply, "error role 'wizard' is not one of host, client, peer");
  reply = service.answer(bytes("register 1 peer 999.0.0.1:4001 10"), 0);
  EXPECT_EQ(reply.rfind("error address '999.0.0.1:4001'", 0), 0u) << reply;
  const std::uint8_t binary[] = {0x00, 0xff, 0x13, 0x80};
  EXPECT_EQ(service.answer(binary, 0).rfind("error ", 0), 0u);
  EXPECT_EQ(service.counters().errors, 3u);
  EXPECT_EQ(service.answer(bytes("list"), 0), "peers 0");
}

}  // namespace
}  // namespace zonesim::topo
