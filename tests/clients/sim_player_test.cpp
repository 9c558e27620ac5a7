// A simulated player against a UDP socket that plays the gateway with crafted datagrams:
// the client verifies everything and counts what it drops.
#include "clients/sim_player.h"

#include <gtest/gtest.h>
#include <poll.h>

#include <cmath>
#include <limits>

#include "common/timer.h"
#include "wire/datagram_checksum.h"

namespace zonesim::clients {
namespace {

using gateway::Bytes;
using gateway::DropReason;

class SimPlayerTest : public ::testing::Test {
 protected:
  SimPlayerTest() {
    PlayerConfig c;
    c.gateway = Endpoint::loopback(gateway_.localPort());
    c.world = {{0, 0, 0}, {100, 10, 100}};
    player_ = std::make_unique<SimPlayer>(c, 0, nowNs());
    player_addr_ = Endpoint::loopback(0);
  }

  // Waits for the next datagram the player sent to the "gateway".
  const proto::Datagram* fromPlayer() {
    pollfd p{gateway_.fd(), POLLIN, 0};
    if (::poll(&p, 1, 2000) <= 0) return nullptr;
    auto got = gateway_.receive(buf_);
    if (!got) return nullptr;
    player_addr_ = got->from;
    auto v =
        gateway::verifyDatagram(std::span(buf_.data(), got->size), gateway::Direction::ToGateway);
    return v.datagram;
  }

  // Sends bytes to the player from `from` and lets it read them.
  void toPlayer(const Bytes& b, gateway::UdpSocket& from) {
    from.sendTo(player_addr_, b);
    pollfd p{player_->fd(), POLLIN, 0};
    ASSERT_EQ(::poll(&p, 1, 2000), 1);
    player_->receive(nowNs());
  }
  void toPlayer(const Bytes& b) { toPlayer(b, gateway_); }

  // Lets the player send its Hello and records the nonce.
  void hello() {
    player_->act(nowNs());
    const proto::Datagram* d = fromPlayer();
    ASSERT_TRUE(d && d->msg_type() == proto::Message::Hello);
    nonce_ = d->msg_as_Hello()->client_nonce();
  }

  // Completes the handshake and returns the token.
  std::uint64_t welcome() {
    if (nonce_ == 0) hello();
    gateway::WelcomeInfo w;
    w.client_nonce = nonce_;
    w.token = 0xabcdef;
    w.player_id = (1ull << 32) | 1;
    w.avatar_id = 77;
    w.zone = 2;
    w.world_max = proto::Vec3f(100, 10, 100);
    toPlayer(gateway::encodeWelcome(w));
    return w.token;
  }

  std::uint64_t dropped(DropReason r) const { return player_->counters().drops[r]; }

  gateway::UdpSocket gateway_;
  std::unique_ptr<SimPlayer> player_;
  Endpoint player_addr_;
  std::uint64_t nonce_ = 0;
  std::vector<std::uint8_t> buf_ = std::vector<std::uint8_t>(2048);
};

// The codec a default Welcome announces.
const dr::StateCodec& codec() {
  static const dr::StateCodec c{dr::CodecParams{}};
  return c;
}

dr::WireEntity state(std::uint64_t id, float x) {
  dr::WireEntity e;
  e.id = id;
  e.tick = 1;
  e.state.pos = {x, 0, 5};
  e.state.vel = {1, 0, 0};
  return e;
}

Bytes spawnOf(std::uint64_t token, std::uint64_t tick, std::vector<dr::WireEntity> v) {
  return gateway::encodeSpawnChunks(token, tick, codec(), v)[0];
}

Bytes updateOf(std::uint64_t token, std::uint64_t tick, std::vector<dr::WireEntity> v) {
  return gateway::encodeStateChunks(token, tick, codec(), v)[0];
}

TEST_F(SimPlayerTest, HandshakeThenInputsAndPings) {
  std::uint64_t token = welcome();
  ASSERT_TRUE(player_->welcomed());
  EXPECT_EQ(player_->avatarId(), 77u);
  EXPECT_EQ(player_->zone(), 2);
  player_->act(nowNs());
  bool input = false, ping = false;
  for (int i = 0; i < 2; ++i) {
    const proto::Datagram* d = fromPlayer();
    ASSERT_NE(d, nullptr);
    EXPECT_EQ(d->token(), token);
    if (d->msg_type() == proto::Message::Input) {
      input = true;
      EXPECT_EQ(d->msg_as_Input()->seq(), 1u);
    }
    ping |= d->msg_type() == proto::Message::Ping;
  }
  EXPECT_TRUE(input && ping);
}

TEST_F(SimPlayerTest, ForgedAndMalformedTrafficIsDroppedByReason) {
  hello();
  std::vector<dr::WireEntity> one{state(5, 1)};
  toPlayer(spawnOf(1, 1, one));  // before any Welcome
  EXPECT_EQ(dropped(DropReason::NotReady), 1u);
  gateway::WelcomeInfo w;
  w.client_nonce = 12345;  // not our nonce
  w.token = 9;
  w.world_max = proto::Vec3f(1, 1, 1);
  toPlayer(gateway::encodeWelcome(w));
  EXPECT_EQ(dropped(DropReason::BadToken), 1u);
  EXPECT_FALSE(player_->welcomed());

  std::uint64_t token = welcome();
  // A frame's checksum is keyed by the token: made with another, it does not check.
  toPlayer(spawnOf(token + 1, 1, one));
  EXPECT_EQ(dropped(DropReason::BadChecksum), 1u);
  toPlayer(gateway::encodePong(token + 1, 1, 2));  // a FlatBuffers datagram carries its token
  EXPECT_EQ(dropped(DropReason::BadToken), 2u);
  gateway::UdpSocket stranger;
  toPlayer(spawnOf(token, 1, one), stranger);  // not from the gateway
  EXPECT_EQ(dropped(DropReason::WrongAddress), 1u);
  toPlayer(Bytes{1, 2, 3});
  toPlayer(Bytes{0xA2, 2, 3});  // byte 0 of a frame
  EXPECT_EQ(dropped(DropReason::Truncated), 2u);
  // A record 90 ticks old in a batch of tick 100, the batch tick rewritten to 50 after
  // packing: the state would predate tick 0, and unpacking refuses it.
  std::vector<dr::WireEntity> early{state(6, 1)};
  early[0].tick = 10;
  Bytes at100 = spawnOf(token, 100, early);
  gateway::ParsedFrame pf = gateway::parseFrame(at100, token);
  ASSERT_TRUE(pf.ok());
  gateway::FrameHeader h = pf.frame.header;
  h.tick = 50;
  toPlayer(gateway::encodeFrame(h, pf.frame.payload, token));
  EXPECT_EQ(dropped(DropReason::OutOfRange), 1u);
  h.count = 9;  // more records than the bytes hold
  toPlayer(gateway::encodeFrame(h, pf.frame.payload, token));
  EXPECT_EQ(dropped(DropReason::OutOfRange), 2u);
  toPlayer(gateway::encodeInput(token, 1, 0, 0));  // a gateway-bound message
  EXPECT_EQ(dropped(DropReason::UnexpectedType), 1u);
  // A Spawn as FlatBuffers: these travel as frames only.
  flatbuffers::FlatBufferBuilder fbb;
  auto v = fbb.CreateVector(pf.frame.payload.data(), pf.frame.payload.size());
  proto::FinishDatagramBuffer(fbb,
                              proto::CreateDatagram(fbb, token, proto::Message::Spawn,
                                                    proto::CreateSpawn(fbb, 100, 1, v).Union()));
  gateway::Bytes flat(fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize());
  gateway::appendChecksum(flat);
  toPlayer(flat);
  EXPECT_EQ(dropped(DropReason::UnexpectedType), 2u);
  EXPECT_EQ(player_->view().size(), 0u) << "nothing dropped reached the view";
}

// The next datagram the "gateway" socket receives, verified (nullptr if none within 2 s).
const proto::Datagram* nextAt(gateway::UdpSocket& gateway, std::vector<std::uint8_t>& buf,
                              Endpoint* from = nullptr) {
  pollfd p{gateway.fd(), POLLIN, 0};
  if (::poll(&p, 1, 2000) != 1) return nullptr;
  auto got = gateway.receive(buf);
  if (!got) return nullptr;
  if (from != nullptr) *from = got->from;
  return gateway::verifyDatagram(std::span(buf.data(), got->size), gateway::Direction::ToGateway)
      .datagram;
}

TEST(SimPlayerLink, HeldDatagramsGoWhenDueEachWayTheByeIncluded) {
  gateway::UdpSocket gateway;
  PlayerConfig c;
  c.gateway = Endpoint::loopback(gateway.localPort());
  c.world = {{0, 0, 0}, {100, 10, 100}};
  c.impairment.out.delay_ms = 5;
  c.impairment.in.delay_ms = 5;
  std::int64_t t0 = nowNs();
  SimPlayer player(c, 0, t0);
  // The Hello goes onto the uplink; the player must wake when it is due, not at its retry.
  std::int64_t next = player.act(t0);
  EXPECT_GE(next, t0 + 5'000'000);
  EXPECT_LT(next, t0 + 250'000'000) << "not at the Hello retry, 0.5 s on";
  EXPECT_EQ(player.impairment().counters().out.delivered, 1u);
  player.act(next);
  std::vector<std::uint8_t> buf(gateway::kMaxDatagramBytes);
  Endpoint player_addr;
  const proto::Datagram* hello = nextAt(gateway, buf, &player_addr);
  ASSERT_TRUE(hello && hello->msg_type() == proto::Message::Hello) << "released when due";
  // The Welcome waits on the downlink until due.
  gateway::WelcomeInfo w;
  w.client_nonce = hello->msg_as_Hello()->client_nonce();
  w.token = 0x5eed;
  w.avatar_id = 9;
  w.world_max = proto::Vec3f(100, 10, 100);
  gateway.sendTo(player_addr, gateway::encodeWelcome(w));
  pollfd p{player.fd(), POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 2000), 1);
  std::int64_t t1 = nowNs();
  player.receive(t1);
  EXPECT_FALSE(player.welcomed()) << "held on the downlink";
  player.act(t1 + 5'000'000);
  ASSERT_TRUE(player.welcomed());
  // A Bye held on the uplink goes out when flushUplink reaches its time.
  player.bye();
  std::int64_t due = player.flushUplink(nowNs());
  ASSERT_NE(due, INT64_MAX) << "held";
  for (int flushes = 0; due != INT64_MAX && flushes < 10; ++flushes) due = player.flushUplink(due);
  EXPECT_EQ(due, INT64_MAX) << "the uplink drained (the Welcome's first input and ping first)";
  const proto::Datagram* d = nextAt(gateway, buf);
  while (d != nullptr && d->msg_type() != proto::Message::Bye) d = nextAt(gateway, buf);
  ASSERT_TRUE(d) << "the Bye went out";
}

TEST_F(SimPlayerTest, SpawnUpdateDespawnAndHandoffAreCounted) {
  std::uint64_t token = welcome();
  std::vector<dr::WireEntity> two{state(5, 1), state(77, 2)};
  toPlayer(spawnOf(token, 1, two));
  EXPECT_EQ(player_->view().size(), 2u);
  EXPECT_EQ(player_->counters().spawns, 2u);
  std::vector<dr::WireEntity> upd{state(5, 3)};
  upd[0].tick = 2;
  toPlayer(updateOf(token, 2, upd));
  EXPECT_EQ(player_->counters().updates, 1u);
  EXPECT_EQ(player_->counters().dr_error_m.seen(), 1u);
  std::vector<std::uint64_t> gone{5};
  toPlayer(gateway::encodeDespawnChunks(token, 3, gone)[0]);
  EXPECT_EQ(player_->view().size(), 1u);
  EXPECT_EQ(player_->counters().despawns, 1u);
  toPlayer(gateway::encodeHandoff(token, {77, 2, 3, 10, 4}));
  EXPECT_EQ(player_->counters().handoffs, 1u);
  EXPECT_EQ(player_->zone(), 3);
  // The avatar is known now: inputs steer toward the wander target.
  player_->act(nowNs());
  const proto::Datagram* d = fromPlayer();
  while (d && d->msg_type() != proto::Message::Input) d = fromPlayer();
  ASSERT_NE(d, nullptr);
  const proto::Input* in = d->msg_as_Input();
  EXPECT_NEAR(std::hypot(in->move_x(), in->move_z()), 1.0, 1e-3);
}

// Numbered datagrams as a resending gateway sends them.
std::uint32_t counter(void* n) {
  return ++*static_cast<std::uint32_t*>(n);
}

TEST_F(SimPlayerTest, AResentHandoffIsAppliedOnceAndAnOlderOneNever) {
  std::uint64_t token = welcome();
  gateway::HandoffInfo h{77, 2, 3, 10, 4, 1};
  toPlayer(gateway::encodeHandoff(token, h));
  h.seq = 2;  // the gateway resends it under a new seq when the ack is late
  toPlayer(gateway::encodeHandoff(token, h));
  EXPECT_EQ(player_->counters().handoffs, 1u);
  EXPECT_EQ(player_->counters().repeats, 1u);
  EXPECT_EQ(player_->acks().ack(), 2u) << "both copies acknowledged";
  // A later handoff, then the earlier one arriving late: the zone stays the later one's.
  toPlayer(gateway::encodeHandoff(token, {77, 3, 1, 40, 9, 4}));
  toPlayer(gateway::encodeHandoff(token, {77, 2, 3, 10, 4, 3}));
  EXPECT_EQ(player_->counters().handoffs, 2u);
  EXPECT_EQ(player_->zone(), 1);
}

TEST_F(SimPlayerTest, TheServerClockRunsAtMostMaxLeadPastTheNewestTick) {
  std::uint64_t token = welcome();
  std::int64_t t0 = nowNs();
  Endpoint from = Endpoint::loopback(gateway_.localPort());
  player_->handle(gateway::encodeClockTick(token, 300), from, t0);
  EXPECT_NEAR(player_->serverTick(t0), 300, 1e-9);
  // 0.1 s later: 3 ticks on at 30 Hz. 2 s later (the zones stalled): max_lead_s (0.25 s) on.
  EXPECT_NEAR(player_->serverTick(t0 + 100'000'000), 303, 1e-6);
  EXPECT_NEAR(player_->serverTick(t0 + 2'000'000'000), 300 + 0.25 * 30, 1e-6);
  // The next tick heard moves the clock on again.
  player_->handle(gateway::encodeClockTick(token, 330), from, t0 + 2'000'000'000);
  EXPECT_NEAR(player_->serverTick(t0 + 2'000'000'000), 330, 1e-9);
}

TEST_F(SimPlayerTest, DuplicatesAndStaleLifecycleAreIgnoredAndAcked) {
  std::uint64_t token = welcome();
  std::uint32_t seq = 0;
  gateway::ChunkSeq numbered{counter, &seq};
  std::vector<dr::WireEntity> one{state(5, 1)};
  Bytes spawn = gateway::encodeSpawnChunks(token, 1, codec(), one, numbered)[0];  // seq 1
  std::vector<std::uint64_t> gone{5};
  Bytes despawn = gateway::encodeDespawnChunks(token, 2, gone, numbered)[0];  // seq 2
  toPlayer(spawn);
  toPlayer(spawn);  // a duplicate
  EXPECT_EQ(player_->counters().duplicates, 1u);
  EXPECT_EQ(player_->counters().spawns, 1u);
  toPlayer(despawn);
  EXPECT_EQ(player_->view().size(), 0u);
  // The spawn resent in a later datagram than the despawn, but built before it: stale.
  seq = 0;
  Bytes late = gateway::encodeSpawnChunks(token, 1, codec(), one, numbered)[0];  // seq 1 again
  Bytes resent_old = late;
  toPlayer(resent_old);
  EXPECT_EQ(player_->view().size(), 0u) << "no ghost: the despawn (seq 2) is newer";
  // A respawn (seq 3) brings it back; the old despawn replayed after it does not remove it.
  seq = 2;
  toPlayer(gateway::encodeSpawnChunks(token, 3, codec(), one, numbered)[0]);
  EXPECT_EQ(player_->view().size(), 1u);
  seq = 1;
  toPlayer(gateway::encodeDespawnChunks(token, 2, gone, numbered)[0]);  // seq 2, duplicate
  EXPECT_EQ(player_->view().size(), 1u);
  EXPECT_EQ(player_->acks().ack(), 3u);
  EXPECT_EQ(player_->acks().bits(), 0b11u);
  // The acks ride on the next input.
  player_->act(nowNs());
  const proto::Datagram* d = fromPlayer();
  while (d && d->msg_type() != proto::Message::Input) d = fromPlayer();
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->msg_as_Input()->ack(), 3u);
  EXPECT_EQ(d->msg_as_Input()->ack_bits(), 0b11u);
}

TEST_F(SimPlayerTest, UpdatesOfAnUnspawnedEntityAreNoticed) {
  std::uint64_t token = welcome();
  std::uint32_t seq = 0;
  gateway::ChunkSeq numbered{counter, &seq};
  std::vector<dr::WireEntity> one{state(9, 1)};
  toPlayer(gateway::encodeStateChunks(token, 1, codec(), one, numbered)[0]);
  EXPECT_EQ(player_->view().size(), 0u);
  toPlayer(gateway::encodeSpawnChunks(token, 2, codec(), one, numbered)[0]);
  EXPECT_EQ(player_->view().size(), 1u);
  EXPECT_EQ(player_->unspawned(), 0u) << "a spawn settles it";
}

TEST_F(SimPlayerTest, ThePongsTimeDilationSlowsTheServerClock) {
  std::uint64_t token = welcome();
  std::int64_t t0 = nowNs();
  Endpoint from = Endpoint::loopback(gateway_.localPort());
  player_->handle(gateway::encodeClockTick(token, 300), from, t0);
  player_->handle(gateway::encodePong(token, 1, 2, 0.5f), from, t0);
  EXPECT_EQ(player_->dilation(), 0.5);
  EXPECT_EQ(player_->counters().min_dilation, 0.5);
  // 0.1 s later at half speed: 1.5 ticks on (3 at full speed); max_lead_s also in dilated time.
  EXPECT_NEAR(player_->serverTick(t0 + 100'000'000), 301.5, 1e-6);
  EXPECT_NEAR(player_->serverTick(t0 + 2'000'000'000), 300 + 0.25 * 15, 1e-6);
  // A factor no gateway sends is dropped and the clock keeps its rate.
  for (float bad : {0.0f, -1.0f, 1.5f, std::numeric_limits<float>::quiet_NaN()})
    player_->handle(gateway::encodePong(token, 1, 2, bad), from, t0);
  EXPECT_EQ(dropped(DropReason::OutOfRange), 4u);
  EXPECT_EQ(player_->dilation(), 0.5);
  // Back to full speed 0.1 s on: the clock keeps its place (301.5) and runs at 30 Hz again.
  player_->handle(gateway::encodePong(token, 1, 2, 1.0f), from, t0 + 100'000'000);
  EXPECT_NEAR(player_->serverTick(t0 + 200'000'000), 304.5, 1e-6);
}

}  // namespace
}  // namespace zonesim::clients
