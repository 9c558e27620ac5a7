// A player reading its socket through a shared ReceiveBatch counts and checks every datagram
// as reading them one by one does: more than one batch's worth is drained, and an oversize one
// is dropped as too large.
#include <gtest/gtest.h>
#include <poll.h>

#include <vector>

#include "clients/sim_player.h"
#include "common/timer.h"

namespace zonesim::clients {
namespace {

TEST(BatchedReceive, DrainsMoreThanABatchAndDropsOversize) {
  gateway::UdpSocket gateway;
  gateway::UdpSocket socket(Endpoint::any(0));
  Endpoint player_at = Endpoint::loopback(socket.localPort());
  PlayerConfig c;
  c.gateway = Endpoint::loopback(gateway.localPort());
  c.world = {{0, 0, 0}, {100, 10, 100}};
  SimPlayer player(c, 0, nowNs(), std::move(socket));

  constexpr std::size_t kSmall = gateway::ReceiveBatch::kBatch * 2 + 5;
  const std::vector<std::uint8_t> junk(12, 0xab);
  const std::vector<std::uint8_t> oversize(gateway::kMaxDatagramBytes + 100, 0xcd);
  for (std::size_t i = 0; i < kSmall; ++i) ASSERT_TRUE(gateway.sendTo(player_at, junk));
  ASSERT_TRUE(gateway.sendTo(player_at, oversize));

  gateway::ReceiveBatch batch(gateway::kMaxDatagramBytes);
  // Loopback queues a datagram as it is sent; the poll is only a bound if the kernel lags.
  while (player.counters().datagrams_in < kSmall + 1) {
    pollfd p{player.fd(), POLLIN, 0};
    ASSERT_EQ(::poll(&p, 1, 2000), 1) << player.counters().datagrams_in;
    player.receive(nowNs(), batch);
  }
  const PlayerCounters& got = player.counters();
  EXPECT_EQ(got.datagrams_in, kSmall + 1);
  EXPECT_EQ(got.bytes_in, kSmall * junk.size() + oversize.size());
  EXPECT_EQ(got.drops[gateway::DropReason::TooLarge], 1u);
  // The rest fail verification: every datagram was looked at, none handled as a message.
  EXPECT_EQ(got.drops.total(), kSmall + 1);
  EXPECT_FALSE(player.welcomed());
}

}  // namespace
}  // namespace zonesim::clients
