// A real Gateway (UDP + DDS) with a real UDP client socket and a test zone made of real DDS
// writers and readers on a private domain: Welcome, Spawn, StateBatch, input routing, Handoff.
#include <gtest/gtest.h>
#include <poll.h>

#include <algorithm>
#include <atomic>
#include <thread>

#include "auth/resume_token.h"
#include "client_read.h"
#include "common/timer.h"
#include "gateway/gateway.h"
#include "gateway_fixture.h"
#include "loopback_gateway_test.h"

namespace zonesim::gateway {
namespace {

using testing::ClientRead;
using testing::entity;

constexpr std::int64_t kTimeoutNs = 15'000'000'000;

class GatewayLoopback : public LoopbackGatewayTest {
 protected:
  void SetUp() override {
    GatewayConfig cfg;
    cfg.scene = testing::smallScene();
    cfg.resume_key = auth::AuthKey(std::vector<std::uint8_t>(32, 0x5c), "test resume key");
    openGateway(cfg);
  }

  // Receives one checked datagram for the client within 20 ms, if any.
  ClientRead receive() {
    pollfd p{client_.fd(), POLLIN, 0};
    if (::poll(&p, 1, 20) <= 0) return {};
    auto got = client_.receive(buf_);
    if (!got || got->from != gateway_addr_) return {};
    return testing::readAsClient(std::span(buf_.data(), got->size), token_);
  }
  // The next Handoff notice within the timeout, or nullptr.
  const proto::Handoff* nextHandoff() {
    std::int64_t deadline = nowNs() + kTimeoutNs;
    while (nowNs() < deadline) {
      ClientRead r = receive();
      if (r.datagram && r.datagram->msg_type() == proto::Message::Handoff)
        return r.datagram->msg_as_Handoff();
    }
    return nullptr;
  }

  // Plays client and zone until the client has its Welcome, both entities and a StateBatch.
  // The client acknowledges what it received, as client_stub does: until its spawns are
  // acknowledged the gateway sends the entities' states as Spawns, not StateBatches.
  std::uint64_t handshakeAndFirstState() {
    std::uint64_t& token = token_;
    std::int64_t deadline = nowNs() + kTimeoutNs, next_hello = 0, next_tick = 0, next_ack = 0;
    while (nowNs() < deadline && !(token && spawned_avatar_ && spawned_npc_ && got_batch_)) {
      if (token == 0 && nowNs() >= next_hello) {
        client_.sendTo(gateway_addr_, encodeHello(hello_nonce_, "tester"));
        next_hello = nowNs() + 500'000'000;
      }
      if (nowNs() >= next_tick) {
        zoneTick();
        next_tick = nowNs() + 33'000'000;
      }
      if (token != 0 && nowNs() >= next_ack) {
        client_.sendTo(gateway_addr_, encodePing(token, 1, acks_.ack(), acks_.bits()));
        next_ack = nowNs() + 50'000'000;
      }
      observe(receive());
    }
    return token;
  }

  // The zone: answers spawn requests, then publishes the avatar and an NPC near it each tick.
  void zoneTick() {
    for (const auto& r : zone_->takeSpawnRequests()) {
      player_ = r.player_id;
      spawn_x_ = r.position.x, spawn_z_ = r.position.z;
      zone_->publishOwnership(player_, kAvatar, -1, 0, tick_, 0);
    }
    if (player_ == 0) return;
    ++tick_;
    auto avatar = entity(kAvatar, 1, spawn_x_, spawn_z_, 1, 0);
    auto npc = entity(kNpc, 0, spawn_x_ + 5, spawn_z_, 0, 1);
    zone_->publishBatch(spawn_x_, spawn_z_, 0, tick_, {}, {avatar, npc});
  }

  void observe(const ClientRead& r) {
    if (r.datagram && r.datagram->msg_type() == proto::Message::Welcome) {
      const proto::Welcome* w = r.datagram->msg_as_Welcome();
      EXPECT_EQ(w->client_nonce(), hello_nonce_);
      EXPECT_EQ(w->avatar_id(), kAvatar);
      EXPECT_EQ(w->player_id(), player_);
      EXPECT_EQ(w->zone(), 0);
      token_ = w->token();
      codec_.emplace(fromProto(*w->codec()));
      welcome_last_input_seq_ = w->last_input_seq();
      if (const auto* t = w->resume_token()) resume_token_.assign(t->begin(), t->end());
    }
    if (!r.frame) return;
    const DownlinkFrame& f = *r.frame;
    acks_.receive(f.header.seq);
    if (f.header.kind == FrameKind::StateBatch) got_batch_ = true;
    if (f.header.kind != FrameKind::Spawn) return;
    ASSERT_TRUE(codec_.has_value());
    auto got = codec_->unpack(f.payload, f.header.count, f.header.tick);
    ASSERT_TRUE(got.has_value());
    for (const dr::WireEntity& s : *got) {
      spawned_avatar_ |= s.id == kAvatar;
      spawned_npc_ |= s.id == kNpc;
    }
  }

  // Sends inputs until the zone reads some on partition z.<zone>.
  std::vector<zonesim_dds_PlayerInput> inputsArrivingAt(int zone, std::uint64_t token) {
    std::vector<zonesim_dds_PlayerInput> inputs;
    std::int64_t deadline = nowNs() + kTimeoutNs;
    while (inputs.empty() && nowNs() < deadline) {
      client_.sendTo(gateway_addr_, encodeInput(token, ++seq_, 0.6f, 0.8f));
      receive();
      inputs = zone_->takeInputs(zone);
    }
    return inputs;
  }

  static constexpr std::uint64_t kAvatar = 0x1000000000001ULL, kNpc = 0x1000000000002ULL;
  std::uint64_t player_ = 0, tick_ = 0, token_ = 0, hello_nonce_ = 99;
  std::uint32_t seq_ = 0, welcome_last_input_seq_ = 0;
  std::vector<std::uint8_t> resume_token_;
  float spawn_x_ = 0, spawn_z_ = 0;
  bool spawned_avatar_ = false, spawned_npc_ = false, got_batch_ = false;
  std::optional<dr::StateCodec> codec_;
  AckWindow acks_;
  UdpSocket client_;
  std::vector<std::uint8_t> buf_ = std::vector<std::uint8_t>(2048);
};

TEST_F(GatewayLoopback, WelcomeSpawnStateBatchInputsAndHandoff) {
  startGateway();
  std::uint64_t token = handshakeAndFirstState();
  ASSERT_NE(token, 0u) << "no Welcome";
  EXPECT_TRUE(spawned_avatar_);
  EXPECT_TRUE(spawned_npc_);
  EXPECT_TRUE(got_batch_);

  // Inputs reach the owning zone's partition.
  std::vector<zonesim_dds_PlayerInput> inputs = inputsArrivingAt(0, token);
  ASSERT_FALSE(inputs.empty());
  EXPECT_EQ(inputs[0].player_id, player_);
  EXPECT_EQ(inputs[0].avatar_id, kAvatar);
  EXPECT_FLOAT_EQ(inputs[0].move_x, 0.6f);

  // Zone 1 takes the avatar over: the client hears of it, later inputs go to z.1.
  zone_->publishOwnership(player_, kAvatar, 0, 1, tick_ + 1, seq_);
  const proto::Handoff* handoff = nextHandoff();
  ASSERT_NE(handoff, nullptr);
  EXPECT_EQ(handoff->from_zone(), 0);
  EXPECT_EQ(handoff->to_zone(), 1);
  EXPECT_EQ(handoff->last_input_seq(), seq_);
  std::uint32_t seq_at_handoff = seq_;
  inputs = inputsArrivingAt(1, token);
  ASSERT_FALSE(inputs.empty());
  EXPECT_GT(inputs[0].seq, seq_at_handoff);
}

TEST_F(GatewayLoopback, AHandoffIsResentUntilAcknowledged) {
  startGateway();
  std::uint64_t token = handshakeAndFirstState();
  ASSERT_NE(token, 0u) << "no Welcome";
  zone_->publishOwnership(player_, kAvatar, 0, 1, tick_ + 1, seq_);
  // The client acknowledges nothing of it: the same notice comes again under a new seq.
  std::vector<std::uint32_t> seqs;
  while (seqs.size() < 2) {
    const proto::Handoff* h = nextHandoff();
    if (h == nullptr) break;
    EXPECT_EQ(h->to_zone(), 1);
    EXPECT_EQ(h->tick(), tick_ + 1);
    seqs.push_back(h->seq());
  }
  ASSERT_EQ(seqs.size(), 2u);
  EXPECT_GT(seqs[1], seqs[0]);
}

// The zones restart from a checkpoint (epoch 1) whose avatar had applied input 2, and now own
// it in zone 2: the gateway resends inputs 3.. to z.2 in order, tells the client of the new
// zone at a tick after every one told before, and ignores what zones of epoch 0 still say.
TEST_F(GatewayLoopback, ARestoredWorldGetsTheLostInputsAndOldEpochsAreIgnored) {
  startGateway();
  std::uint64_t token = handshakeAndFirstState();
  ASSERT_NE(token, 0u) << "no Welcome";
  ASSERT_FALSE(inputsArrivingAt(0, token).empty());
  while (seq_ < 6) inputsArrivingAt(0, token);
  const std::uint32_t sent = seq_;
  zone_->takeInputs(2);  // zone 2's reader, matched before it is resent to
  std::int64_t settle = nowNs() + 300'000'000;
  while (nowNs() < settle) receive();

  const std::uint64_t restored_tick = 5;  // earlier than any tick the gateway has seen
  zone_->publishOwnership(player_, kAvatar, -1, 2, restored_tick, 2, /*epoch=*/1);
  const proto::Handoff* handoff = nextHandoff();
  ASSERT_NE(handoff, nullptr);
  EXPECT_EQ(handoff->to_zone(), 2);
  EXPECT_EQ(handoff->avatar_id(), kAvatar);
  EXPECT_GT(handoff->tick(), tick_) << "the restored world's ticks continue the gateway's";
  std::vector<std::uint32_t> resent;
  std::int64_t deadline = nowNs() + 3'000'000'000;
  while (nowNs() < deadline && resent.size() < sent - 2) {
    for (const zonesim_dds_PlayerInput& in : zone_->takeInputs(2))
      if (std::find(resent.begin(), resent.end(), in.seq) == resent.end()) resent.push_back(in.seq);
    receive();
  }
  std::vector<std::uint32_t> expected;
  for (std::uint32_t s = 3; s <= sent; ++s) expected.push_back(s);
  EXPECT_EQ(resent, expected) << "inputs 3.." << sent << " resent in order";

  // A late word from epoch 0 moves nothing: new inputs still go to zone 2.
  zone_->publishOwnership(player_, kAvatar, 2, 3, tick_ + 100, sent, /*epoch=*/0);
  settle = nowNs() + 300'000'000;
  while (nowNs() < settle) receive();
  std::vector<zonesim_dds_PlayerInput> later = inputsArrivingAt(2, token);
  ASSERT_FALSE(later.empty());
  EXPECT_GT(later.back().seq, sent);
  EXPECT_TRUE(zone_->takeInputs(3).empty());
}

// The gateway dies with the player in play (inputs 1..6 or more sent, the zone applied 1..4
// when it last said); a restarted one takes the player back with its resume token: the same
// player and avatar, a Welcome naming input 4, and inputs after it reach the zone in order.
TEST_F(GatewayLoopback, ARestartedGatewayResumesThePlayerWithItsToken) {
  startGateway();
  ASSERT_NE(handshakeAndFirstState(), 0u) << "no Welcome";
  ASSERT_EQ(resume_token_.size(), auth::kResumeTokenBytes);
  while (seq_ < 6) inputsArrivingAt(0, token_);
  const std::uint64_t player = player_, old_token = token_;
  const std::uint32_t sent = seq_, last = sent + 2;

  restartGateway();
  zone_->takeInputs(0);  // stragglers of the first session
  token_ = 0;
  hello_nonce_ = 100;  // a resuming client says Hello anew
  bool asked = false;
  std::int64_t deadline = nowNs() + kTimeoutNs, next_hello = 0;
  while (nowNs() < deadline && token_ == 0) {
    if (nowNs() >= next_hello) {
      client_.sendTo(gateway_addr_, encodeHello(hello_nonce_, "tester", {}, 0, resume_token_));
      next_hello = nowNs() + 200'000'000;
    }
    // The zone knows the player: it re-announces the avatar where it is, with input 4 applied.
    for (const auto& r : zone_->takeSpawnRequests()) {
      EXPECT_EQ(r.player_id, player) << "the token's player, not a new one";
      asked = true;
      zone_->publishOwnership(player, kAvatar, -1, 0, tick_, 4);
    }
    observe(receive());
  }
  ASSERT_TRUE(asked) << "no spawn request from the restarted gateway";
  ASSERT_NE(token_, 0u) << "no Welcome from the restarted gateway";
  EXPECT_NE(token_, old_token) << "a new session";
  EXPECT_EQ(welcome_last_input_seq_, 4u);
  EXPECT_EQ(gateway_->counters().sessions_resumed, 1u);

  // The client resends 5.. and goes on: the zone reads them in order, none twice.
  std::vector<std::uint32_t> got;
  deadline = nowNs() + kTimeoutNs;
  std::uint32_t next = welcome_last_input_seq_;
  while (nowNs() < deadline && (got.empty() || got.back() < last)) {
    if (next < last) client_.sendTo(gateway_addr_, encodeInput(token_, ++next, 0.6f, 0.8f));
    for (const zonesim_dds_PlayerInput& in : zone_->takeInputs(0)) {
      EXPECT_EQ(in.player_id, player);
      EXPECT_EQ(in.avatar_id, kAvatar);
      got.push_back(in.seq);
    }
    receive();
  }
  std::vector<std::uint32_t> expected;
  for (std::uint32_t s = 5; s <= last; ++s) expected.push_back(s);
  EXPECT_EQ(got, expected) << "inputs 5.." << sent << " resent, then new ones";
}

TEST_F(GatewayLoopback, ForgedTrafficIsCountedAndHarmless) {
  client_.sendTo(gateway_addr_, Bytes{0xde, 0xad, 0xbe, 0xef, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  client_.sendTo(gateway_addr_, encodeInput(12345, 1, 0, 1));
  client_.sendTo(gateway_addr_, Bytes(kMaxDatagramBytes + 100, 0x5a));
  // The datagrams wait in the socket; short runs on this thread read them, for as long as a
  // loaded machine takes to schedule it (one fixed-length run may end before the first read).
  std::int64_t deadline = nowNs() + kTimeoutNs;
  while (gateway_->counters().datagrams_in < 3 && nowNs() < deadline) gateway_->run(stop_, 0.05);
  EXPECT_EQ(gateway_->drops()[DropReason::BadChecksum], 1u);
  EXPECT_EQ(gateway_->drops()[DropReason::BadToken], 1u);
  EXPECT_EQ(gateway_->drops()[DropReason::TooLarge], 1u);
  EXPECT_EQ(gateway_->counters().datagrams_in, 3u);
}

// Cyclone announces each participant to every discovery port of its domain on 127.0.0.1: a test
// socket that drew one of them would count RTPS datagrams as drops.
TEST(PrivateDdsDomain, NoTestSocketCanDrawItsPorts) {
  auto [lo, hi] = testing::detail::ephemeralPorts();
  if (testing::detail::domainsClearOfEphemeralPorts().empty())
    GTEST_SKIP() << "the ephemeral port range " << lo << "-" << hi << " spans every domain";
  int d = testing::privateDdsDomain();
  int first = testing::detail::kDdsPortBase + testing::detail::kDdsDomainGain * d;
  int last = first + testing::detail::kDdsDomainGain - 1;
  EXPECT_TRUE(last < lo || first > hi) << "domain " << d << " uses ports " << first << "-" << last;
}

}  // namespace
}  // namespace zonesim::gateway
