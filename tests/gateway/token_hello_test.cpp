// A gateway with the cluster's key against crafted Hellos: a valid connect token opens a session
// for the token's player; a missing, forged, expired, other gateway's, replayed-from-elsewhere or
// reused token opens nothing and is counted under its own reason. Without a key, tokens are
// ignored and nothing changes.
#include <gtest/gtest.h>

#include "auth/connect_token.h"
#include "gateway/datagram_handler.h"
#include "gateway/gateway_metrics.h"

namespace zonesim::gateway {
namespace {

constexpr std::uint16_t kGatewayId = 2;
constexpr std::uint64_t kNowMs = 1'800'000'000'000;
constexpr std::uint64_t kPlayer =
    (std::uint64_t{0x77} << 48) | (std::uint64_t{kGatewayId} << 32) | 5;

auth::AuthKey key(std::uint8_t seed = 1) {
  std::vector<std::uint8_t> b(32);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::uint8_t(seed * 7 + i);
  return auth::AuthKey(b, "test key");
}

class TokenHelloTest : public ::testing::Test {
 protected:
  TokenHelloTest() : sessions_(kGatewayId, 8), handler_(sessions_, config()) {}

  HandlerConfig config() {
    HandlerConfig c;
    c.world = {{-50, 0, -50}, {50, 10, 50}};
    c.auth_key = key();
    c.gateway_id = kGatewayId;
    c.unix_now_ms = [this] { return now_ms_; };
    return c;
  }

  static auth::ConnectToken grant(const Endpoint& to = kClient, std::uint64_t player = kPlayer) {
    auth::ConnectToken t;
    t.player_id = player;
    t.gateway_id = kGatewayId;
    t.client_address = to.address;
    t.client_port = to.port;
    t.expiry_unix_ms = kNowMs + 30'000;
    return t;
  }

  static Bytes hello(std::uint64_t nonce, std::span<const std::uint8_t> token) {
    return encodeHello(nonce, "p", token);
  }

  void feed(const Bytes& b, const Endpoint& from = kClient) {
    out_.clear();
    handler_.handle(b, from, ++now_ns_, out_);
  }

  std::uint64_t dropped(DropReason r) const { return handler_.drops()[r]; }

  static inline const Endpoint kClient{0x0a4d0003, 45000};  // 10.77.0.3:45000
  static inline const Endpoint kOtherPort{0x0a4d0003, 45001};
  static inline const Endpoint kOtherHost{0x0a4d0004, 45000};
  SessionTable sessions_;
  std::uint64_t now_ms_ = kNowMs;
  DatagramHandler handler_;
  Outbox out_;
  std::int64_t now_ns_ = 0;
};

TEST_F(TokenHelloTest, ValidTokenOpensASessionForTheTokensPlayer) {
  auth::TokenBytes t = auth::signToken(grant(), key());
  feed(hello(42, t));
  ASSERT_EQ(sessions_.size(), 1u);
  ASSERT_EQ(out_.spawns.size(), 1u);
  EXPECT_EQ(out_.spawns[0].player_id, kPlayer) << "the lobby's id, not one issued here";
  EXPECT_EQ(handler_.drops().total(), 0u);
  EXPECT_EQ(handler_.tokenGate()->admitted(), 1u);
  // A retry of the same Hello (lost Welcome) is the same session, not a reuse.
  feed(hello(42, t));
  EXPECT_EQ(sessions_.size(), 1u);
  EXPECT_TRUE(out_.spawns.empty());
  EXPECT_EQ(dropped(DropReason::TokenReused), 0u);
}

TEST_F(TokenHelloTest, HelloWithoutTokenIsRefused) {
  feed(encodeHello(42, "p"));
  EXPECT_EQ(sessions_.size(), 0u);
  EXPECT_TRUE(out_.spawns.empty());
  EXPECT_EQ(dropped(DropReason::TokenMissing), 1u);
}

TEST_F(TokenHelloTest, ForgedTokensAreRefused) {
  auth::TokenBytes t = auth::signToken(grant(), key());
  auth::TokenBytes flipped = t;
  flipped[40] ^= 0x10;  // in the tag
  auth::TokenBytes raised = t;
  raised[17] ^= 0x01;  // the expiry, with the tag left as it was
  auth::TokenBytes other_key = auth::signToken(grant(), key(9));
  std::vector<std::uint8_t> junk(auth::kConnectTokenBytes, 0xab);
  std::vector<std::uint8_t> short_one(t.begin(), t.begin() + 20);
  std::uint64_t nonce = 1;
  for (std::span<const std::uint8_t> bad :
       {std::span<const std::uint8_t>(flipped), std::span<const std::uint8_t>(raised),
        std::span<const std::uint8_t>(other_key), std::span<const std::uint8_t>(junk),
        std::span<const std::uint8_t>(short_one)})
    feed(hello(nonce++, bad));
  EXPECT_EQ(dropped(DropReason::TokenForged), 5u);
  EXPECT_EQ(sessions_.size(), 0u);
  EXPECT_EQ(handler_.drops().total(), 5u);
}

TEST_F(TokenHelloTest, ExpiredTokenIsRefused) {
  auth::TokenBytes t = auth::signToken(grant(), key());
  now_ms_ = kNowMs + 30'000;
  feed(hello(42, t));
  EXPECT_EQ(dropped(DropReason::TokenExpired), 1u);
  EXPECT_EQ(sessions_.size(), 0u);
}

TEST_F(TokenHelloTest, TokenForAnotherGatewayIsRefused) {
  auth::ConnectToken g = grant();
  g.gateway_id = kGatewayId + 1;
  feed(hello(42, auth::signToken(g, key())));
  EXPECT_EQ(dropped(DropReason::TokenWrongGateway), 1u);
  EXPECT_EQ(sessions_.size(), 0u);
}

TEST_F(TokenHelloTest, TokenReplayedFromAnotherAddressIsRefused) {
  auth::TokenBytes t = auth::signToken(grant(), key());
  feed(hello(42, t), kOtherPort);
  feed(hello(42, t), kOtherHost);
  EXPECT_EQ(dropped(DropReason::TokenWrongAddress), 2u);
  EXPECT_EQ(sessions_.size(), 0u);
  // The replays did not use the token up: its owner still gets in.
  feed(hello(42, t), kClient);
  EXPECT_EQ(sessions_.size(), 1u);
  // And a replay while the owner plays changes nothing either.
  feed(hello(43, t), kOtherHost);
  EXPECT_EQ(dropped(DropReason::TokenWrongAddress), 3u);
  EXPECT_EQ(sessions_.size(), 1u);
}

TEST_F(TokenHelloTest, ATokenOpensOneSessionOnly) {
  auth::TokenBytes t = auth::signToken(grant(), key());
  feed(hello(42, t));
  ASSERT_EQ(sessions_.size(), 1u);
  // Another Hello (another nonce) with the same token while the session is open...
  feed(hello(43, t));
  EXPECT_EQ(dropped(DropReason::TokenReused), 1u);
  // ... and after the session ended.
  Session* s = sessions_.get(*sessions_.findByHello(kClient, 42));
  feed(encodeBye(s->token));
  ASSERT_EQ(sessions_.size(), 0u);
  feed(hello(44, t));
  EXPECT_EQ(dropped(DropReason::TokenReused), 2u);
  EXPECT_EQ(sessions_.size(), 0u);
  // Once expired it is refused as expired (and forgotten).
  now_ms_ = kNowMs + 40'000;
  feed(hello(45, t));
  EXPECT_EQ(dropped(DropReason::TokenExpired), 1u);
  EXPECT_EQ(handler_.tokenGate()->remembered(), 0u);
}

TEST_F(TokenHelloTest, RefusalsAreNamedInTheSummary) {
  feed(encodeHello(42, "p"));
  auth::ConnectToken g = grant();
  g.gateway_id = 9;
  feed(hello(43, auth::signToken(g, key())));
  std::string summary = summaryJson({}, handler_.drops(), {}, {});
  EXPECT_NE(summary.find("\"token_missing\":1"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"token_wrong_gateway\":1"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"token_forged\":0"), std::string::npos) << summary;
  std::string line = metricsLine({}, handler_.drops(), {}).str();
  EXPECT_NE(line.find("\"dropped_token_missing\":1"), std::string::npos) << line;
}

// Without a key the gateway is as it was: a token in a Hello is ignored, ids are its own.
TEST(TokenHelloWithoutKey, TokensAreIgnored) {
  SessionTable sessions(kGatewayId, 8);
  HandlerConfig c;
  c.world = {{-50, 0, -50}, {50, 10, 50}};
  DatagramHandler handler(sessions, c);
  EXPECT_EQ(handler.tokenGate(), nullptr);
  Outbox out;
  std::vector<std::uint8_t> junk(57, 1);
  handler.handle(encodeHello(1, "p", junk), Endpoint::loopback(4000), 1, out);
  handler.handle(encodeHello(2, "p"), Endpoint::loopback(4001), 2, out);
  EXPECT_EQ(sessions.size(), 2u);
  ASSERT_EQ(out.spawns.size(), 2u);
  EXPECT_EQ(out.spawns[0].player_id, (std::uint64_t{kGatewayId} << 32) | 1);
  EXPECT_EQ(handler.drops().total(), 0u);
}

// The Hello without a token is the same bytes as before tokens existed.
TEST(TokenHelloWithoutKey, HelloWithoutTokenHasNoTokenField) {
  Bytes b = encodeHello(7, "p");
  Verified v = verifyDatagram(b, Direction::ToGateway);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v.datagram->msg_as_Hello()->connect_token(), nullptr);
  std::vector<std::uint8_t> too_long(kMaxConnectTokenBytes + 1, 1);
  EXPECT_EQ(verifyDatagram(encodeHello(7, "p", too_long), Direction::ToGateway).reason,
            DropReason::OutOfRange);
}

}  // namespace
}  // namespace zonesim::gateway
