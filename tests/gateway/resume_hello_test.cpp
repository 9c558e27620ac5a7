// A gateway with the cluster's resume key against crafted Hellos: each Welcome carries a resume
// token and the last input the zone applied; a Hello with the token, to this gateway or to
// another of the cluster, opens a session for the token's player and kind, replacing a live
// one of the same player; a forged, expired or replayed-from-elsewhere token, or any token at a
// gateway without the key, opens nothing and is counted under its own reason.
#include <gtest/gtest.h>

#include "auth/resume_token.h"
#include "gateway/datagram_handler.h"
#include "gateway/gateway_metrics.h"

namespace zonesim::gateway {
namespace {

constexpr std::uint64_t kNowMs = 1'800'000'000'000;

auth::AuthKey key(std::uint8_t seed = 1) {
  std::vector<std::uint8_t> b(32);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::uint8_t(seed * 5 + i);
  return auth::AuthKey(b, "test key");
}

// One gateway of the cluster: its own sessions, the shared key.
struct TestGateway {
  TestGateway(std::uint16_t id, const std::uint64_t* now_ms, std::optional<auth::AuthKey> k)
      : sessions(id, 8), handler(sessions, config(now_ms, std::move(k))) {}

  static HandlerConfig config(const std::uint64_t* now_ms, std::optional<auth::AuthKey> k) {
    HandlerConfig c;
    c.world = {{-50, 0, -50}, {50, 10, 50}};
    c.kinds = 0b111;  // walkers, riders and flyers
    c.resume_key = std::move(k);
    c.resume_valid_s = 60;
    c.unix_now_ms = [now_ms] { return *now_ms; };
    return c;
  }

  void feed(const Bytes& b, const Endpoint& from) {
    out.clear();
    handler.handle(b, from, ++now_ns, out);
  }

  // A session whose avatar the zones announced, with inputs applied up to last_seq.
  Session& welcomed(std::uint64_t nonce, const Endpoint& from, std::uint8_t kind,
                    std::uint32_t last_seq) {
    feed(encodeHello(nonce, "p", {}, kind), from);
    Session* s = sessions.get(*sessions.findByHello(from, nonce));
    s->avatar_id = 1001;
    s->zone = 0;
    s->welcomed = true;
    s->last_input_seq = last_seq;
    return *s;
  }

  std::uint64_t dropped(DropReason r) const { return handler.drops()[r]; }

  SessionTable sessions;
  DatagramHandler handler;
  Outbox out;
  std::int64_t now_ns = 0;
};

class ResumeHelloTest : public ::testing::Test {
 protected:
  // The resume token of a welcomed session's Welcome.
  std::vector<std::uint8_t> resumeTokenOf(const Session& s) {
    Bytes w = a_.handler.welcomeFor(s);
    Verified v = verifyDatagram(w, Direction::ToClient);
    EXPECT_TRUE(v.ok());
    const auto* t = v.datagram->msg_as_Welcome()->resume_token();
    return t ? std::vector<std::uint8_t>(t->begin(), t->end()) : std::vector<std::uint8_t>{};
  }

  static Bytes resumeHello(std::uint64_t nonce, std::span<const std::uint8_t> token) {
    return encodeHello(nonce, "p", {}, 0, token);
  }

  static inline const Endpoint kClient{0x0a4d0003, 45000};  // 10.77.0.3:45000
  static inline const Endpoint kOtherPort{0x0a4d0003, 45001};
  std::uint64_t now_ms_ = kNowMs;
  TestGateway a_{1, &now_ms_, key()};
  TestGateway b_{2, &now_ms_, key()};
};

TEST_F(ResumeHelloTest, WelcomeCarriesAResumeTokenAndTheLastAppliedInput) {
  Session& s = a_.welcomed(42, kClient, 1, 6);
  Verified v = verifyDatagram(a_.handler.welcomeFor(s), Direction::ToClient);
  ASSERT_TRUE(v.ok());
  const proto::Welcome* w = v.datagram->msg_as_Welcome();
  EXPECT_EQ(w->last_input_seq(), 6u);
  ASSERT_NE(w->resume_token(), nullptr);
  std::span<const std::uint8_t> t(w->resume_token()->data(), w->resume_token()->size());
  auth::ResumeVerdict r = auth::checkResume(t, key(), kClient.address, kClient.port, kNowMs);
  ASSERT_EQ(r.check, auth::ResumeCheck::Ok);
  EXPECT_EQ(r.token.player_id, s.player_id);
  EXPECT_EQ(r.token.kind, 1u);
  EXPECT_EQ(r.token.expiry_unix_ms, kNowMs + 60'000);
}

// Gateway a died; b, another of the cluster, takes the player back as itself.
TEST_F(ResumeHelloTest, AnotherGatewayOpensASessionForTheTokensPlayerAndKind) {
  Session& s = a_.welcomed(42, kClient, 2, 6);
  std::uint64_t player = s.player_id;
  std::vector<std::uint8_t> t = resumeTokenOf(s);
  b_.feed(resumeHello(77, t), kClient);  // the Hello itself says kind 0
  ASSERT_EQ(b_.sessions.size(), 1u);
  ASSERT_EQ(b_.out.spawns.size(), 1u);
  EXPECT_EQ(b_.out.spawns[0].player_id, player) << "the token's player, not an id issued at b";
  EXPECT_EQ(b_.out.spawns[0].kind, 2u) << "the token's kind";
  EXPECT_TRUE(b_.out.spawns[0].resumed);
  Session* resumed = b_.sessions.get(*b_.sessions.findByPlayer(player));
  EXPECT_TRUE(resumed->resumed);
  EXPECT_FALSE(resumed->welcomed) << "welcomed when the zone re-announces the avatar";
  EXPECT_EQ(b_.handler.drops().total(), 0u);
  // A retry of the same Hello is the same session.
  b_.feed(resumeHello(77, t), kClient);
  EXPECT_EQ(b_.sessions.size(), 1u);
  EXPECT_TRUE(b_.out.spawns.empty());
}

// The player thought its gateway dead while it was not: the new session replaces the old.
TEST_F(ResumeHelloTest, AResumeReplacesALiveSessionOfThePlayer) {
  Session& s = a_.welcomed(42, kClient, 0, 6);
  std::uint64_t player = s.player_id, old_token = s.token;
  std::vector<std::uint8_t> t = resumeTokenOf(s);
  a_.feed(resumeHello(43, t), kClient);
  ASSERT_EQ(a_.out.replaced.size(), 1u);
  EXPECT_EQ(a_.out.replaced[0].token, old_token);
  EXPECT_TRUE(a_.out.closed.empty()) << "replaced, not ended: the avatar goes on";
  ASSERT_EQ(a_.sessions.size(), 1u);
  Session* now = a_.sessions.get(*a_.sessions.findByPlayer(player));
  EXPECT_NE(now->token, old_token);
  EXPECT_EQ(a_.sessions.findByToken(old_token), std::nullopt);
  ASSERT_EQ(a_.out.spawns.size(), 1u);
  EXPECT_EQ(a_.out.spawns[0].player_id, player);
}

// A player may lose several gateways: the token of its first Welcome still works at the third.
TEST_F(ResumeHelloTest, OneTokenResumesMoreThanOnce) {
  std::vector<std::uint8_t> t = resumeTokenOf(a_.welcomed(42, kClient, 0, 6));
  b_.feed(resumeHello(43, t), kClient);
  TestGateway c(3, &now_ms_, key());
  c.feed(resumeHello(44, t), kClient);
  EXPECT_EQ(b_.sessions.size(), 1u);
  EXPECT_EQ(c.sessions.size(), 1u);
}

TEST_F(ResumeHelloTest, BadResumeTokensAreRefusedByReason) {
  std::vector<std::uint8_t> t = resumeTokenOf(a_.welcomed(42, kClient, 0, 6));
  std::vector<std::uint8_t> flipped = t;
  flipped[10] ^= 0x01;  // the player id, with the tag left as it was
  b_.feed(resumeHello(1, flipped), kClient);
  TestGateway other_cluster(2, &now_ms_, key(9));
  other_cluster.feed(resumeHello(2, t), kClient);
  b_.feed(resumeHello(3, t), kOtherPort);
  EXPECT_EQ(b_.dropped(DropReason::ResumeForged), 1u);
  EXPECT_EQ(other_cluster.dropped(DropReason::ResumeForged), 1u);
  EXPECT_EQ(b_.dropped(DropReason::ResumeWrongAddress), 1u);
  now_ms_ = kNowMs + 60'000;
  b_.feed(resumeHello(4, t), kClient);
  EXPECT_EQ(b_.dropped(DropReason::ResumeExpired), 1u);
  EXPECT_EQ(b_.sessions.size(), 0u);
  EXPECT_EQ(other_cluster.sessions.size(), 0u);
  EXPECT_EQ(b_.handler.drops().total(), 3u);
  std::string summary = summaryJson({}, b_.handler.drops(), {}, {});
  EXPECT_NE(summary.find("\"resume_expired\":1"), std::string::npos) << summary;
}

// A gateway without the key cannot tell a token from junk: refused, never a new player.
TEST_F(ResumeHelloTest, AGatewayWithoutTheKeyRefusesEveryResume) {
  std::vector<std::uint8_t> t = resumeTokenOf(a_.welcomed(42, kClient, 0, 6));
  TestGateway keyless(2, &now_ms_, std::nullopt);
  keyless.feed(resumeHello(43, t), kClient);
  EXPECT_EQ(keyless.dropped(DropReason::ResumeForged), 1u);
  EXPECT_EQ(keyless.sessions.size(), 0u);
  // And its Welcomes carry no token: its players start over when it dies.
  Session& s = keyless.welcomed(44, kClient, 0, 0);
  Verified v = verifyDatagram(keyless.handler.welcomeFor(s), Direction::ToClient);
  ASSERT_TRUE(v.ok());
  EXPECT_EQ(v.datagram->msg_as_Welcome()->resume_token(), nullptr);
}

// With a lobby, a resumed player needs no connect token: it was admitted when it first came.
TEST_F(ResumeHelloTest, AResumeNeedsNoConnectToken) {
  std::vector<std::uint8_t> t = resumeTokenOf(a_.welcomed(42, kClient, 0, 6));
  SessionTable sessions(2, 8);
  HandlerConfig c = TestGateway::config(&now_ms_, key());
  c.auth_key = key(3);
  c.gateway_id = 2;
  DatagramHandler gated(sessions, c);
  Outbox out;
  gated.handle(resumeHello(43, t), kClient, 1, out);
  EXPECT_EQ(sessions.size(), 1u);
  EXPECT_EQ(gated.drops().total(), 0u);
  gated.handle(encodeHello(44, "p"), kClient, 2, out);
  EXPECT_EQ(gated.drops()[DropReason::TokenMissing], 1u) << "a new player still needs one";
}

}  // namespace
}  // namespace zonesim::gateway
