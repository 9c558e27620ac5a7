// The login service against crafted datagrams: a request gets a token the gateway it names
// accepts from that address only; a retry gets the same grant; no gateway or none with room is
// a refusal worth retrying; bad datagrams are dropped and counted.
#include "lobby/login_service.h"

#include <gtest/gtest.h>

#include "auth/connect_token.h"

namespace zonesim::lobby {
namespace {

constexpr std::uint64_t kUnixMs = 1'800'000'000'000;

auth::AuthKey key(std::uint8_t seed = 3) {
  std::vector<std::uint8_t> b(32);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = std::uint8_t(seed + 5 * i);
  return auth::AuthKey(b, "test key");
}

class LoginServiceTest : public ::testing::Test {
 protected:
  LoginServiceTest() : directory_(3'000'000'000), service_(key(), directory_, settings()) {}

  static LoginSettings settings() {
    LoginSettings s;
    s.token_lifetime_ms = 20'000;
    s.incarnation = 0x77;
    return s;
  }

  void addGateway(std::uint16_t id, std::uint32_t sessions, std::uint32_t max = 100) {
    GatewayReport r;
    r.gateway_id = id;
    r.incarnation = 1;
    r.address = {0x0a4d0000u + id, std::uint16_t(7000 + id)};
    r.sessions = sessions;
    r.max_sessions = max;
    directory_.report(r, 0);
  }

  const lobby_proto::LobbyDatagram* ask(std::uint64_t nonce, const gateway::Endpoint& from) {
    auto reply = service_.handle(gateway::encodeLoginRequest(nonce, "p"), from, 0, kUnixMs);
    if (!reply) return nullptr;
    last_ = *reply;
    gateway::LobbyVerified v =
        gateway::verifyLobbyDatagram(last_, gateway::LobbyDirection::ToPlayer);
    EXPECT_TRUE(v.ok());
    return v.datagram;
  }

  static inline const gateway::Endpoint kPlayer{0x0a4d0009, 40000};
  GatewayDirectory directory_;
  LoginService service_;
  gateway::Bytes last_;
};

TEST_F(LoginServiceTest, GrantsATokenForTheLeastLoadedGatewayBoundToTheSender) {
  addGateway(1, 5);
  addGateway(2, 3);
  const auto* d = ask(11, kPlayer);
  ASSERT_NE(d, nullptr);
  const auto* g = d->msg_as_LoginGranted();
  ASSERT_NE(g, nullptr);
  EXPECT_EQ(g->request_nonce(), 11u);
  EXPECT_EQ(g->gateway_id(), 2);
  EXPECT_EQ(g->gateway_address(), 0x0a4d0002u);
  EXPECT_EQ(g->gateway_port(), 7002);
  EXPECT_EQ(g->expiry_unix_ms(), kUnixMs + 20'000);
  EXPECT_EQ(g->player_id(), (std::uint64_t{0x77} << 48) | (std::uint64_t{2} << 32) | 1);
  std::span<const std::uint8_t> token(g->connect_token()->data(), g->connect_token()->size());
  // The gateway it names accepts it from the sender, and no one else does.
  auth::TokenVerdict v = auth::checkToken(token, key(), 2, kPlayer.address, kPlayer.port, kUnixMs);
  EXPECT_EQ(v.check, auth::TokenCheck::Ok);
  EXPECT_EQ(v.token.player_id, g->player_id());
  EXPECT_EQ(auth::checkToken(token, key(), 1, kPlayer.address, kPlayer.port, kUnixMs).check,
            auth::TokenCheck::WrongGateway);
  EXPECT_EQ(auth::checkToken(token, key(), 2, kPlayer.address, kPlayer.port + 1, kUnixMs).check,
            auth::TokenCheck::WrongAddress);
  EXPECT_EQ(auth::checkToken(token, key(9), 2, kPlayer.address, kPlayer.port, kUnixMs).check,
            auth::TokenCheck::Forged);
  EXPECT_EQ(service_.counters().granted, 1u);
}

TEST_F(LoginServiceTest, ARetryGetsTheSameGrant) {
  addGateway(1, 0);
  addGateway(2, 0);
  ASSERT_NE(ask(11, kPlayer), nullptr);
  gateway::Bytes first = last_;
  ASSERT_NE(ask(11, kPlayer), nullptr);
  EXPECT_EQ(last_, first);
  EXPECT_EQ(service_.counters().granted, 1u);
  EXPECT_EQ(service_.counters().repeated, 1u);
  EXPECT_EQ(directory_.entries().at(1).granted + directory_.entries().at(2).granted, 1u);
  // Another nonce, or the same nonce from elsewhere, is another player.
  const auto* d = ask(12, kPlayer);
  EXPECT_EQ(d->msg_as_LoginGranted()->gateway_id(), 2) << "1 has one grant in flight";
  ask(11, {kPlayer.address, 40001});
  EXPECT_EQ(service_.counters().granted, 3u);
}

TEST_F(LoginServiceTest, NoGatewayIsARefusalWorthRetrying) {
  const auto* d = ask(11, kPlayer);
  ASSERT_NE(d, nullptr);
  const auto* r = d->msg_as_LoginRefused();
  ASSERT_NE(r, nullptr);
  EXPECT_TRUE(r->retry());
  EXPECT_NE(r->reason()->str().find("no gateway"), std::string::npos);
  EXPECT_EQ(service_.counters().refused_no_gateway, 1u);
  // Refusals are not remembered: once a gateway reports, the retry is granted.
  addGateway(1, 0);
  d = ask(11, kPlayer);
  ASSERT_NE(d->msg_as_LoginGranted(), nullptr);
}

TEST(LoginServiceStart, LoginsWaitForTheExpectedGateways) {
  GatewayDirectory directory(3'000'000'000);
  LoginSettings s;
  s.expect_gateways = 2;
  LoginService service(key(), directory, s);
  auto ask = [&](std::uint64_t nonce) {
    auto reply =
        service.handle(gateway::encodeLoginRequest(nonce, "p"), {0x0a4d0009, 40000}, 0, kUnixMs);
    return gateway::verifyLobbyDatagram(*reply, gateway::LobbyDirection::ToPlayer)
        .datagram->msg_type();
  };
  GatewayReport r;
  r.gateway_id = 1;
  r.address = {0x0a4d0001, 7001};
  r.max_sessions = 10;
  directory.report(r, 0);
  EXPECT_EQ(ask(1), lobby_proto::LobbyMessage::LoginRefused);
  EXPECT_EQ(service.counters().refused_starting, 1u);
  r.gateway_id = 2;
  directory.report(r, 0);
  EXPECT_EQ(ask(2), lobby_proto::LobbyMessage::LoginGranted);
  // Started: one gateway going silent later does not stop the logins.
  r.gateway_id = 1;
  directory.report(r, 3'500'000'000);
  EXPECT_EQ(
      service
          .handle(gateway::encodeLoginRequest(3, "p"), {0x0a4d0009, 40000}, 3'500'000'000, kUnixMs)
          .has_value(),
      true);
  EXPECT_EQ(service.counters().granted, 2u);
}

TEST_F(LoginServiceTest, AllFullIsARefusal) {
  addGateway(1, 2, 2);
  const auto* d = ask(11, kPlayer);
  ASSERT_NE(d->msg_as_LoginRefused(), nullptr);
  EXPECT_NE(d->msg_as_LoginRefused()->reason()->str().find("full"), std::string::npos);
  EXPECT_EQ(service_.counters().refused_full, 1u);
}

TEST_F(LoginServiceTest, BadDatagramsAreDroppedAndCounted) {
  addGateway(1, 0);
  gateway::Bytes b = gateway::encodeLoginRequest(11, "p");
  b[6] ^= 1;
  EXPECT_FALSE(service_.handle(b, kPlayer, 0, kUnixMs));
  EXPECT_FALSE(service_.handle(gateway::encodeHello(11, "p"), kPlayer, 0, kUnixMs));
  EXPECT_FALSE(service_.handle(gateway::encodeLoginRefused(11, true, "x"), kPlayer, 0, kUnixMs));
  EXPECT_FALSE(service_.handle(gateway::encodeLoginRequest(0, "p"), kPlayer, 0, kUnixMs));
  const gateway::DropCounters& d = service_.drops();
  EXPECT_EQ(d[gateway::DropReason::BadChecksum], 1u);
  EXPECT_EQ(d[gateway::DropReason::BadIdentifier], 1u);
  EXPECT_EQ(d[gateway::DropReason::UnexpectedType], 1u);
  EXPECT_EQ(d[gateway::DropReason::OutOfRange], 1u);
  EXPECT_EQ(service_.counters().requests, 0u);
  EXPECT_EQ(service_.counters().granted, 0u);
}

}  // namespace
}  // namespace zonesim::lobby
