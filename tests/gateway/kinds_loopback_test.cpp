// Player kinds through a real gateway: a walker and a flyer say Hello with their kinds, the
// zones' spawn requests carry them, and each player's interest is its kind's nimbus: an NPC
// between the walker's and the flyer's nimbus from each avatar is shown to the flyer and never
// to the walker. The gateway's summary counts the sessions per kind.
#include <gtest/gtest.h>
#include <poll.h>

#include <map>
#include <set>

#include "client_read.h"
#include "common/timer.h"
#include "gateway/gateway.h"
#include "gateway_fixture.h"
#include "loopback_gateway_test.h"

namespace zonesim::gateway {
namespace {

using testing::entity;

constexpr std::int64_t kTimeoutNs = 20'000'000'000;
constexpr double kWalkerNimbus = 15, kFlyerNimbus = 45;
// Between the two nimbi, and beyond the walker's keep radius (1.1 x its nimbus).
constexpr double kNpcDistance = 30;
// Zone ticks the walker must have been told about after its own spawn before its view counts
// as settled (its NPC would have come with its own avatar's spawn, had it been in view).
constexpr int kSettledBatches = 30;

Scene kindsScene() {
  Scene s = testing::smallScene();
  s.clients.kinds = {{PlayerKindId::Walker, 5, kWalkerNimbus, 0, 0.5},
                     {PlayerKindId::Flyer, 30, kFlyerNimbus, 10, 0.5}};
  return s;
}

/// One player on its own socket: says Hello until welcomed, acknowledges what it gets, and
/// remembers every entity it was spawned.
struct Player {
  explicit Player(std::uint64_t nonce, PlayerKindId kind) : nonce(nonce), kind(kind) {}
  std::uint64_t nonce;
  PlayerKindId kind;
  UdpSocket socket;
  std::uint64_t token = 0, avatar = 0;
  std::optional<dr::StateCodec> codec;
  AckWindow acks;
  std::set<std::uint64_t> spawned;
  int batches_since_own_spawn = 0;
  std::int64_t next_hello = 0, next_ack = 0;

  void act(const Endpoint& gateway) {
    std::int64_t now = nowNs();
    if (token == 0 && now >= next_hello) {
      socket.sendTo(gateway, encodeHello(nonce, "kind", {}, std::uint8_t(kind)));
      next_hello = now + 500'000'000;
    }
    if (token != 0 && now >= next_ack) {
      socket.sendTo(gateway, encodePing(token, 1, acks.ack(), acks.bits()));
      next_ack = now + 50'000'000;
    }
  }

  void receiveAll(const Endpoint& gateway) {
    std::vector<std::uint8_t> buf(2048);
    while (auto got = socket.receive(buf)) {
      if (got->from != gateway) continue;
      observe(testing::readAsClient(std::span(buf.data(), got->size), token));
    }
  }

  void observe(const testing::ClientRead& r) {
    if (r.datagram && r.datagram->msg_type() == proto::Message::Welcome) {
      const proto::Welcome* w = r.datagram->msg_as_Welcome();
      if (w->client_nonce() != nonce) return;
      token = w->token();
      avatar = w->avatar_id();
      codec.emplace(fromProto(*w->codec()));
      return;
    }
    if (!r.frame) return;
    const DownlinkFrame& f = *r.frame;
    switch (f.header.kind) {
      case FrameKind::Spawn: {
        acks.receive(f.header.seq);
        ASSERT_TRUE(codec.has_value());
        auto got = codec->unpack(f.payload, f.header.count, f.header.tick);
        ASSERT_TRUE(got.has_value());
        for (const dr::WireEntity& e : *got) spawned.insert(e.id);
        return;
      }
      case FrameKind::StateBatch:
        acks.receive(f.header.seq);
        if (spawned.contains(avatar)) ++batches_since_own_spawn;
        return;
      default:
        return;
    }
  }
};

class KindsLoopback : public LoopbackGatewayTest {
 protected:
  void SetUp() override {
    GatewayConfig cfg;
    cfg.scene = kindsScene();
    cfg.clock_every_ticks = 1;  // a StateBatch every tick: the walker's settling is counted
    openGateway(cfg);
  }

  struct Avatar {
    std::uint64_t id;
    float x, z;
    std::uint8_t kind;
  };

  // The zone: answers spawn requests, then publishes each avatar and, kNpcDistance from it, an
  // NPC of its own (id avatar + 1000), grouped into one batch per cell.
  void zoneTick() {
    for (const auto& r : zone_->takeSpawnRequests()) {
      if (avatars_.contains(r.player_id)) continue;
      Avatar a{0x1000000000001ULL + avatars_.size(), r.position.x, r.position.z, r.kind};
      avatars_.emplace(r.player_id, a);
      zone_->publishOwnership(r.player_id, a.id, -1, 0, tick_, 0);
    }
    if (avatars_.empty()) return;
    ++tick_;
    std::map<int, std::vector<zonesim_dds_EntityUpdate>> by_cell;
    InterestGrid grid(kindsScene().world, kindsScene().interest_cell_size);
    for (const auto& [player, a] : avatars_) {
      float npc_x =
          a.x + kNpcDistance < 100 ? a.x + float(kNpcDistance) : a.x - float(kNpcDistance);
      by_cell[grid.cellOf(a.x, a.z)].push_back(entity(a.id, 1, a.x, a.z));
      by_cell[grid.cellOf(npc_x, a.z)].push_back(entity(npcOf(a), 0, npc_x, a.z));
    }
    for (auto& [cell, entities] : by_cell) {
      float x = entities[0].pos.x, z = entities[0].pos.z;
      zone_->publishBatch(x, z, 0, tick_, {}, entities);
    }
  }

  static std::uint64_t npcOf(const Avatar& a) { return a.id + 1000; }

  std::map<std::uint64_t, Avatar> avatars_;  // by player id
  std::uint64_t tick_ = 0;
};

TEST_F(KindsLoopback, AFlyerSeesWhatAWalkerBesideItDoesNot) {
  startGateway();
  Player walker(1, PlayerKindId::Walker), flyer(2, PlayerKindId::Flyer);
  auto npcSeenBy = [&](const Player& p) {
    for (const auto& [player, a] : avatars_)
      if (a.id == p.avatar) return p.spawned.contains(npcOf(a));
    return false;
  };
  std::int64_t deadline = nowNs() + kTimeoutNs, next_tick = 0;
  while (nowNs() < deadline &&
         !(npcSeenBy(flyer) && walker.batches_since_own_spawn >= kSettledBatches)) {
    walker.act(gateway_addr_);
    flyer.act(gateway_addr_);
    if (nowNs() >= next_tick) {
      zoneTick();
      next_tick = nowNs() + 33'000'000;
    }
    pollfd p[2] = {{walker.socket.fd(), POLLIN, 0}, {flyer.socket.fd(), POLLIN, 0}};
    ::poll(p, 2, 5);
    walker.receiveAll(gateway_addr_);
    flyer.receiveAll(gateway_addr_);
  }
  ASSERT_EQ(avatars_.size(), 2u);
  std::set<std::uint8_t> kinds;
  for (const auto& [player, a] : avatars_) kinds.insert(a.kind);
  EXPECT_EQ(kinds, (std::set<std::uint8_t>{0, std::uint8_t(PlayerKindId::Flyer)}))
      << "the spawn requests carry each player's kind";
  ASSERT_NE(walker.token, 0u);
  ASSERT_NE(flyer.token, 0u);
  EXPECT_TRUE(flyer.spawned.contains(flyer.avatar));
  EXPECT_TRUE(npcSeenBy(flyer)) << "an NPC " << kNpcDistance << " m away, inside the flyer's "
                                << kFlyerNimbus << " m nimbus";
  ASSERT_TRUE(walker.spawned.contains(walker.avatar));
  EXPECT_GE(walker.batches_since_own_spawn, kSettledBatches);
  EXPECT_FALSE(npcSeenBy(walker)) << "an NPC " << kNpcDistance << " m away, beyond the walker's "
                                  << kWalkerNimbus << " m nimbus";

  stop_ = true;
  thread_.join();
  std::string summary = gateway_->summaryJson();
  EXPECT_NE(summary.find("\"sessions_by_kind\":{\"walker\":1,\"rider\":0,\"flyer\":1}"),
            std::string::npos)
      << summary;
}

TEST_F(KindsLoopback, AKindTheSceneLacksOpensNoSession) {
  Player rider(3, PlayerKindId::Rider);
  rider.act(gateway_addr_);
  // The gateway runs on this thread, in short runs, until it has read the Hello (as long as a
  // loaded machine takes); its counters are then safe to read.
  std::int64_t deadline = nowNs() + kTimeoutNs;
  while (gateway_->counters().datagrams_in < 1 && nowNs() < deadline) {
    gateway_->run(stop_, 0.05);
    zoneTick();
    rider.receiveAll(gateway_addr_);
  }
  EXPECT_EQ(gateway_->drops()[DropReason::UnknownKind], 1u);
  EXPECT_TRUE(avatars_.empty()) << "no spawn request for a refused Hello";
  EXPECT_EQ(rider.token, 0u);
}

}  // namespace
}  // namespace zonesim::gateway
