// The datagram handler against crafted datagrams: each bad one dropped and counted by the right
// reason, the good ones accepted with the right effects.
#include "gateway/datagram_handler.h"

#include <gtest/gtest.h>

#include <limits>

#include "wire/datagram_checksum.h"

namespace zonesim::gateway {
namespace {

class HandlerTest : public ::testing::Test {
 protected:
  HandlerTest() : sessions_(2, 8), handler_(sessions_, config()) {}

  static HandlerConfig config() {
    HandlerConfig c;
    c.world = {{-50, 0, -50}, {50, 10, 50}};
    c.tick_rate = 30;
    c.spawn_seed = 3;
    return c;
  }

  void feed(const Bytes& b, const Endpoint& from = kClient) {
    out_.clear();
    handler_.handle(b, from, ++now_, out_);
  }

  // A session that said Hello and whose avatar the zones announced.
  Session& welcomedSession() {
    feed(encodeHello(42, "p"));
    Session* s = sessions_.get(*sessions_.findByHello(kClient, 42));
    s->avatar_id = 1001;
    s->zone = 0;
    s->welcomed = true;
    return *s;
  }

  std::uint64_t dropped(DropReason r) const { return handler_.drops()[r]; }

  static inline const Endpoint kClient = Endpoint::loopback(45000);
  static inline const Endpoint kOther = Endpoint::loopback(45001);
  SessionTable sessions_;
  DatagramHandler handler_;
  Outbox out_;
  std::int64_t now_ = 0;
};

TEST_F(HandlerTest, HelloCreatesOneSessionAndOneSpawnRequest) {
  feed(encodeHello(42, "p"));
  ASSERT_EQ(sessions_.size(), 1u);
  ASSERT_EQ(out_.spawns.size(), 1u);
  const SpawnCommand& c = out_.spawns[0];
  EXPECT_EQ(c.player_id, (std::uint64_t{2} << 32) | 1);
  EXPECT_GE(c.x, -50);
  EXPECT_LE(c.x, 50);
  EXPECT_EQ(c.y, 0);
  EXPECT_TRUE(out_.replies.empty()) << "no Welcome before the zone answers";
  // The client retries while pending: same nonce, same address -> nothing new.
  feed(encodeHello(42, "p"));
  EXPECT_EQ(sessions_.size(), 1u);
  EXPECT_TRUE(out_.spawns.empty());
  EXPECT_TRUE(out_.replies.empty());
  // The same nonce from another address is another client.
  feed(encodeHello(42, "p"), kOther);
  EXPECT_EQ(sessions_.size(), 2u);
}

TEST_F(HandlerTest, RepeatedHelloAfterWelcomeResendsTheWelcome) {
  Session& s = welcomedSession();
  feed(encodeHello(42, "p"));
  ASSERT_EQ(out_.replies.size(), 1u);
  Verified v = verifyDatagram(out_.replies[0].bytes, Direction::ToClient);
  ASSERT_TRUE(v.ok());
  const proto::Welcome* w = v.datagram->msg_as_Welcome();
  EXPECT_EQ(w->token(), s.token);
  EXPECT_EQ(w->client_nonce(), 42u);
  EXPECT_EQ(w->avatar_id(), 1001u);
  EXPECT_EQ(w->world_min()->x(), -50);
  EXPECT_EQ(sessions_.size(), 1u);
}

TEST_F(HandlerTest, MalformedDatagramsAreCountedByReason) {
  Bytes garbage{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  feed(garbage);
  Bytes hello = encodeHello(42, "p");
  feed(Bytes(hello.begin(), hello.begin() + 6));
  Bytes wrong_id = hello;
  wrong_id[5] = '!';
  feed(wrong_id);
  EXPECT_EQ(dropped(DropReason::BadChecksum), 2u);  // the garbage and the changed byte
  // Sealed again, the same bytes reach the identifier check.
  garbage.resize(garbage.size() - kChecksumBytes);
  appendChecksum(garbage);
  feed(garbage);
  wrong_id.resize(wrong_id.size() - kChecksumBytes);
  appendChecksum(wrong_id);
  feed(wrong_id);
  EXPECT_EQ(dropped(DropReason::BadIdentifier), 2u);  // garbage has no ZSCP identifier either
  EXPECT_EQ(dropped(DropReason::Truncated), 1u);
  EXPECT_EQ(sessions_.size(), 0u);
  EXPECT_EQ(handler_.accepted(), 0u);
}

TEST_F(HandlerTest, ForgedTokenIsDropped) {
  Session& s = welcomedSession();
  feed(encodeInput(s.token ^ 1, 1, 0, 1));
  EXPECT_EQ(dropped(DropReason::BadToken), 1u);
  EXPECT_TRUE(out_.inputs.empty());
}

TEST_F(HandlerTest, RightTokenFromWrongAddressIsDropped) {
  Session& s = welcomedSession();
  feed(encodeInput(s.token, 1, 0, 1), kOther);
  feed(encodeBye(s.token), kOther);
  EXPECT_EQ(dropped(DropReason::WrongAddress), 2u);
  EXPECT_TRUE(out_.inputs.empty());
  EXPECT_EQ(sessions_.size(), 1u) << "a Bye from elsewhere must not end the session";
}

TEST_F(HandlerTest, OutOfRangeMoveAndNaNAreDropped) {
  Session& s = welcomedSession();
  feed(encodeInput(s.token, 1, 0.9f, 0.9f));
  feed(encodeInput(s.token, 2, std::numeric_limits<float>::quiet_NaN(), 0));
  EXPECT_EQ(dropped(DropReason::OutOfRange), 2u);
  EXPECT_TRUE(out_.inputs.empty());
}

TEST_F(HandlerTest, ValidInputIsForwardedOnceInOrder) {
  Session& s = welcomedSession();
  feed(encodeInput(s.token, 1, 0.6f, -0.8f));
  ASSERT_EQ(out_.inputs.size(), 1u);
  const InputCommand& c = out_.inputs[0];
  EXPECT_EQ(c.player_id, s.player_id);
  EXPECT_EQ(c.avatar_id, 1001u);
  EXPECT_EQ(c.zone, 0);
  EXPECT_EQ(c.seq, 1u);
  EXPECT_FLOAT_EQ(c.move_x, 0.6f);
  EXPECT_FLOAT_EQ(c.move_z, -0.8f);
  feed(encodeInput(s.token, 1, 0, 0));  // duplicate
  EXPECT_TRUE(out_.inputs.empty());
  EXPECT_EQ(dropped(DropReason::StaleInput), 1u);
  feed(encodeInput(s.token, 3, 0, 0));  // 2 was lost: fine, still in order
  EXPECT_EQ(out_.inputs.size(), 1u);
}

// An input whose datagram was lost reaches the zone from the next one, which carries it again:
// in order, before the newer one, and once.
TEST_F(HandlerTest, AnInputCarriedAgainStandsInForOneLost) {
  Session& s = welcomedSession();
  feed(encodeInput(s.token, 1, 0, 1));
  std::vector<InputRecord> earlier{{1, 0, 1}, {2, 0.6f, 0}};  // 2's own datagram was lost
  feed(encodeInput(s.token, 3, 0, -1, 0, 0, earlier));
  ASSERT_EQ(out_.inputs.size(), 2u);
  EXPECT_EQ(out_.inputs[0].seq, 2u);
  EXPECT_FLOAT_EQ(out_.inputs[0].move_x, 0.6f);
  EXPECT_EQ(out_.inputs[1].seq, 3u);
  EXPECT_EQ(handler_.inputsRecovered(), 1u);
  std::vector<InputRecord> again{{2, 0.6f, 0}, {3, 0, -1}};
  feed(encodeInput(s.token, 4, 0, 0, 0, 0, again));
  ASSERT_EQ(out_.inputs.size(), 1u) << "2 and 3 went on already";
  EXPECT_EQ(out_.inputs[0].seq, 4u);
  EXPECT_EQ(handler_.inputsRecovered(), 1u);
}

// Every copy of a transaction goes to the avatar's zone, repeats too (the zone answers a
// repeat with the outcome the client missed); before the Welcome it is not ready.
TEST_F(HandlerTest, TransactionsGoToTheAvatarsZoneRepeatsIncluded) {
  feed(encodeHello(42, "p"));
  Session* early = sessions_.get(*sessions_.findByHello(kClient, 42));
  feed(encodeTransaction(early->token, {1, 2, 7, 1}));
  EXPECT_TRUE(out_.transactions.empty());
  EXPECT_EQ(dropped(DropReason::NotReady), 1u);
  Session& s = welcomedSession();
  s.zone = 3;
  TransactionInfo t{1, 3, 12, 1, 0, 40, 0};
  for (int copy = 0; copy < 2; ++copy) {
    feed(encodeTransaction(s.token, t));
    ASSERT_EQ(out_.transactions.size(), 1u) << "copy " << copy;
    EXPECT_EQ(out_.transactions[0].player_id, s.player_id);
    EXPECT_EQ(out_.transactions[0].zone, 3);
    EXPECT_EQ(out_.transactions[0].tx, t);
  }
  feed(encodeTransaction(s.token ^ 1, t));
  EXPECT_TRUE(out_.transactions.empty());
  EXPECT_EQ(dropped(DropReason::BadToken), 1u);
}

TEST_F(HandlerTest, InputBeforeWelcomeIsNotReady) {
  feed(encodeHello(42, "p"));
  const Session* s = sessions_.get(*sessions_.findByHello(kClient, 42));
  feed(encodeInput(s->token, 1, 0, 0));
  EXPECT_EQ(dropped(DropReason::NotReady), 1u);
}

TEST_F(HandlerTest, PingGetsPongAndByeEndsTheSession) {
  Session& s = welcomedSession();
  std::uint64_t token = s.token, player = s.player_id;
  feed(encodePing(token, 123456));
  ASSERT_EQ(out_.replies.size(), 1u);
  Verified v = verifyDatagram(out_.replies[0].bytes, Direction::ToClient);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v.datagram->msg_as_Pong()->client_time_us(), 123456u);
  EXPECT_EQ(out_.replies[0].to, kClient);
  feed(encodeBye(token));
  ASSERT_EQ(out_.closed.size(), 1u);
  EXPECT_EQ(out_.closed[0].player_id, player);
  EXPECT_EQ(sessions_.size(), 0u);
  feed(encodePing(token, 1));
  EXPECT_EQ(dropped(DropReason::BadToken), 1u) << "the token died with the session";
}

TEST_F(HandlerTest, ASessionSendingTooFastIsRateLimited) {
  Session& s = welcomedSession();
  HandlerConfig c = config();
  // 200 inputs in the same instant: the burst (50) passes, the rest is dropped and counted.
  std::uint32_t seq = 0;
  std::size_t forwarded = 0;
  for (int i = 0; i < 200; ++i) {
    out_.clear();
    handler_.handle(encodeInput(s.token, ++seq, 0, 0), kClient, 1'000'000, out_);
    forwarded += out_.inputs.size();
  }
  EXPECT_EQ(forwarded, std::size_t(c.rate_burst));
  EXPECT_EQ(dropped(DropReason::RateLimited), 200 - forwarded);
  // Half a second later the bucket holds rate * 0.5 = 50 tokens again (capped at the burst).
  forwarded = 0;
  for (int i = 0; i < 60; ++i) {
    out_.clear();
    handler_.handle(encodeInput(s.token, ++seq, 0, 0), kClient, 501'000'000, out_);
    forwarded += out_.inputs.size();
  }
  EXPECT_EQ(forwarded, std::size_t(c.rate_burst));
  // A client within the rate (20 inputs a second) never hits it.
  std::uint64_t before = dropped(DropReason::RateLimited);
  for (int i = 0; i < 100; ++i)
    handler_.handle(encodeInput(s.token, ++seq, 0, 0), kClient, 2'000'000'000 + i * 50'000'000LL,
                    out_);
  EXPECT_EQ(dropped(DropReason::RateLimited), before);
}

TEST_F(HandlerTest, GatewayBoundMessagesOnlyAndSessionLimit) {
  feed(encodePong(1, 2, 3));
  EXPECT_EQ(dropped(DropReason::UnexpectedType), 1u);
  for (std::uint64_t n = 1; n <= 9; ++n) feed(encodeHello(n, "p"));
  EXPECT_EQ(sessions_.size(), 8u);
  EXPECT_EQ(dropped(DropReason::SessionLimit), 1u);
}

TEST_F(HandlerTest, SpawnPositionsAreReproducibleForASeed) {
  SessionTable other_sessions(2, 8);
  DatagramHandler other(other_sessions, config());
  Outbox other_out;
  for (std::uint64_t n = 1; n <= 3; ++n) {
    feed(encodeHello(n, "p"));
    other.handle(encodeHello(n, "p"), kClient, 0, other_out);
    ASSERT_EQ(out_.spawns.size(), 1u);
    EXPECT_EQ(out_.spawns[0].x, other_out.spawns.back().x);
    EXPECT_EQ(out_.spawns[0].z, other_out.spawns.back().z);
  }
}

}  // namespace
}  // namespace zonesim::gateway

namespace zonesim::gateway {
namespace {

// Random corruptions of valid datagrams: each is either accepted or dropped with a reason, and
// nothing crashes (run under the sanitizers this also checks no out-of-bounds read).
TEST(HandlerFuzz, CorruptedDatagramsAreAcceptedOrCountedNeverFatal) {
  SessionTable sessions(1, 8);
  HandlerConfig config;
  config.world = {{0, 0, 0}, {10, 10, 10}};
  DatagramHandler handler(sessions, config);
  Pcg32 rng(2024, 1);
  std::vector<Bytes> seeds{encodeHello(5, "fuzz"), encodeInput(7, 3, 0.5f, 0.5f), encodePing(7, 1),
                           encodeBye(7)};
  const Endpoint from = Endpoint::loopback(45100);
  Outbox out;
  constexpr int kRuns = 20000;
  for (int i = 0; i < kRuns; ++i) {
    // The body mutated and sealed again, so the checks behind the checksum see it.
    Bytes b = seeds[rng.next() % seeds.size()];
    b.resize(b.size() - kChecksumBytes);
    int flips = 1 + int(rng.next() % 4);
    for (int f = 0; f < flips; ++f) b[rng.next() % b.size()] = std::uint8_t(rng.next());
    if (rng.next() % 8 == 0) b.resize(rng.next() % (b.size() + 1));
    appendChecksum(b);
    out.clear();
    handler.handle(b, from, i, out);
  }
  EXPECT_EQ(handler.accepted() + handler.drops().total(), std::uint64_t(kRuns));
  EXPECT_GT(handler.drops()[DropReason::Malformed] + handler.drops()[DropReason::BadIdentifier],
            0u);
}

}  // namespace
}  // namespace zonesim::gateway
