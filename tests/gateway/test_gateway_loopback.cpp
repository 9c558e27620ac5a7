// A real Gateway (UDP + DDS) with a real UDP client socket and a test zone made of real DDS
// writers and readers on a private domain: Welcome, Spawn, StateBatch, input routing, Handoff.
#include <gtest/gtest.h>
#include <poll.h>

#include <atomic>
#include <thread>

#include "common/timer.h"
#include "gateway/gateway.h"
#include "test_support.h"

namespace zonesim::gateway {
namespace {

using testing::entity;

constexpr std::int64_t kTimeoutNs = 15'000'000'000;

class GatewayLoopback : public ::testing::Test {
 protected:
  void SetUp() override {
    int domain = testing::privateDdsDomain();
    GatewayConfig cfg;
    cfg.scene = testing::smallScene();
    cfg.dds_domain = domain;
    cfg.expected_zones = 1;
    gateway_ = std::make_unique<Gateway>(cfg);
    zone_ = std::make_unique<testing::ZoneEmulator>(domain, cfg.scene);
    gateway_addr_ = Endpoint::loopback(gateway_->port());
  }
  void TearDown() override {
    stop_ = true;
    if (thread_.joinable()) thread_.join();
  }
  void startGateway() {
    thread_ = std::thread([this] { gateway_->run(stop_); });
  }

  // Receives one verified datagram for the client within 20 ms, if any.
  const proto::Datagram* receive() {
    pollfd p{client_.fd(), POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) return nullptr;
    auto got = client_.receive(buf_);
    if (!got || got->from != gateway_addr_) return nullptr;
    Verified v = verifyDatagram(std::span(buf_.data(), got->size), Direction::ToClient);
    EXPECT_TRUE(v.ok()) << dropReasonName(v.reason);
    return v.datagram;
  }

  std::unique_ptr<Gateway> gateway_;
  std::unique_ptr<testing::ZoneEmulator> zone_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
  UdpSocket client_;
  Endpoint gateway_addr_;
  std::vector<std::uint8_t> buf_ = std::vector<std::uint8_t>(2048);
};

TEST_F(GatewayLoopback, WelcomeSpawnStateBatchInputsAndHandoff) {
  const std::uint64_t kAvatar = 0x1000000000001ULL, kNpc = 0x1000000000002ULL;
  std::uint64_t token = 0, player = 0, tick = 0;
  float spawn_x = 0, spawn_z = 0;
  startGateway();
  bool spawned_avatar = false, spawned_npc = false, got_batch = false;
  std::int64_t deadline = nowNs() + kTimeoutNs, next_hello = 0, next_tick = 0;
  while (nowNs() < deadline && !(token && spawned_avatar && spawned_npc && got_batch)) {
    if (token == 0 && nowNs() >= next_hello) {
      client_.sendTo(gateway_addr_, encodeHello(99, "tester"));
      next_hello = nowNs() + 500'000'000;
    }
    // The zone: answer spawn requests, then publish a batch every tick near the avatar.
    for (const auto& r : zone_->takeSpawnRequests()) {
      player = r.player_id;
      spawn_x = r.position.x, spawn_z = r.position.z;
      zone_->publishOwnership(player, kAvatar, -1, 0, tick, 0);
    }
    if (player != 0 && nowNs() >= next_tick) {
      ++tick;
      auto avatar = entity(kAvatar, 1, spawn_x, spawn_z, 1, 0);
      auto npc = entity(kNpc, 0, spawn_x + 5, spawn_z, 0, 1);
      zone_->publishBatch(spawn_x, spawn_z, 0, tick, {}, {avatar, npc});
      next_tick = nowNs() + 33'000'000;
    }
    const proto::Datagram* d = receive();
    if (d == nullptr) continue;
    switch (d->msg_type()) {
      case proto::Message::Welcome:
        EXPECT_EQ(d->msg_as_Welcome()->client_nonce(), 99u);
        EXPECT_EQ(d->msg_as_Welcome()->avatar_id(), kAvatar);
        EXPECT_EQ(d->msg_as_Welcome()->player_id(), player);
        EXPECT_EQ(d->msg_as_Welcome()->zone(), 0);
        token = d->msg_as_Welcome()->token();
        break;
      case proto::Message::Spawn:
        for (const proto::EntityState* s : *d->msg_as_Spawn()->entities()) {
          spawned_avatar |= s->id() == kAvatar;
          spawned_npc |= s->id() == kNpc;
        }
        break;
      case proto::Message::StateBatch:
        got_batch = true;
        break;
      default:
        break;
    }
  }
  ASSERT_NE(token, 0u) << "no Welcome";
  EXPECT_TRUE(spawned_avatar);
  EXPECT_TRUE(spawned_npc);
  EXPECT_TRUE(got_batch);

  // Inputs reach the owning zone's partition.
  std::vector<zonesim_dds_PlayerInput> inputs;
  std::uint32_t seq = 0;
  deadline = nowNs() + kTimeoutNs;
  while (inputs.empty() && nowNs() < deadline) {
    client_.sendTo(gateway_addr_, encodeInput(token, ++seq, 0.6f, 0.8f));
    receive();
    inputs = zone_->takeInputs(0);
  }
  ASSERT_FALSE(inputs.empty());
  EXPECT_EQ(inputs[0].player_id, player);
  EXPECT_EQ(inputs[0].avatar_id, kAvatar);
  EXPECT_FLOAT_EQ(inputs[0].move_x, 0.6f);

  // Zone 1 takes the avatar over: the client hears of it, later inputs go to z.1.
  zone_->publishOwnership(player, kAvatar, 0, 1, tick + 1, seq);
  bool handoff = false;
  deadline = nowNs() + kTimeoutNs;
  while (!handoff && nowNs() < deadline) {
    const proto::Datagram* d = receive();
    if (d && d->msg_type() == proto::Message::Handoff) {
      EXPECT_EQ(d->msg_as_Handoff()->from_zone(), 0);
      EXPECT_EQ(d->msg_as_Handoff()->to_zone(), 1);
      EXPECT_EQ(d->msg_as_Handoff()->last_input_seq(), seq);
      handoff = true;
    }
  }
  ASSERT_TRUE(handoff);
  inputs.clear();
  deadline = nowNs() + kTimeoutNs;
  while (inputs.empty() && nowNs() < deadline) {
    client_.sendTo(gateway_addr_, encodeInput(token, ++seq, 0, 1));
    receive();
    inputs = zone_->takeInputs(1);
  }
  ASSERT_FALSE(inputs.empty());
  EXPECT_GT(inputs[0].seq, 1u);
}

TEST_F(GatewayLoopback, ForgedTrafficIsCountedAndHarmless) {
  client_.sendTo(gateway_addr_, Bytes{0xde, 0xad, 0xbe, 0xef, 1, 2, 3, 4, 5, 6});
  client_.sendTo(gateway_addr_, encodeInput(12345, 1, 0, 1));
  client_.sendTo(gateway_addr_, Bytes(kMaxDatagramBytes + 100, 0x5a));
  // The datagrams wait in the socket; a short run on this thread handles them all.
  gateway_->run(stop_, 0.3);
  EXPECT_EQ(gateway_->drops()[DropReason::BadIdentifier], 1u);
  EXPECT_EQ(gateway_->drops()[DropReason::BadToken], 1u);
  EXPECT_EQ(gateway_->drops()[DropReason::TooLarge], 1u);
  EXPECT_EQ(gateway_->counters().datagrams_in, 3u);
}

}  // namespace
}  // namespace zonesim::gateway
