// The lobby protocol's encoders and checks: each message round-trips, goes one way only, and a
// corrupted, truncated or out-of-range datagram is dropped with the right reason.
#include "wire/lobby_wire.h"

#include <gtest/gtest.h>

namespace zonesim::gateway {
namespace {

TEST(LobbyWire, GrantRoundTrips) {
  std::vector<std::uint8_t> token(57, 0x5a);
  LoginGrant g{9, 0x1234, 3, {0x0a4d0003, 7777}, 1'800'000'000'000, token};
  Bytes b = encodeLoginGranted(g);
  LobbyVerified v = verifyLobbyDatagram(b, LobbyDirection::ToPlayer);
  ASSERT_TRUE(v.ok());
  const auto* m = v.datagram->msg_as_LoginGranted();
  EXPECT_EQ(m->request_nonce(), 9u);
  EXPECT_EQ(m->player_id(), 0x1234u);
  EXPECT_EQ(m->gateway_id(), 3);
  EXPECT_EQ(m->gateway_address(), 0x0a4d0003u);
  EXPECT_EQ(m->gateway_port(), 7777);
  EXPECT_EQ(m->expiry_unix_ms(), 1'800'000'000'000u);
  EXPECT_EQ(std::vector<std::uint8_t>(m->connect_token()->begin(), m->connect_token()->end()),
            token);
}

TEST(LobbyWire, EachMessageGoesOneWay) {
  EXPECT_TRUE(verifyLobbyDatagram(encodeLoginRequest(1, "p"), LobbyDirection::ToLobby).ok());
  EXPECT_EQ(verifyLobbyDatagram(encodeLoginRequest(1, "p"), LobbyDirection::ToPlayer).reason,
            DropReason::UnexpectedType);
  EXPECT_TRUE(verifyLobbyDatagram(encodeLoginRefused(1, true, "x"), LobbyDirection::ToPlayer).ok());
  EXPECT_EQ(verifyLobbyDatagram(encodeLoginRefused(1, true, "x"), LobbyDirection::ToLobby).reason,
            DropReason::UnexpectedType);
}

TEST(LobbyWire, BadDatagramsAreDroppedByReason) {
  Bytes b = encodeLoginRequest(1, "p");
  EXPECT_EQ(verifyLobbyDatagram(std::span(b).first(6), LobbyDirection::ToLobby).reason,
            DropReason::Truncated);
  Bytes flipped = b;
  flipped[b.size() / 2] ^= 4;
  EXPECT_EQ(verifyLobbyDatagram(flipped, LobbyDirection::ToLobby).reason, DropReason::BadChecksum);
  EXPECT_EQ(verifyLobbyDatagram(encodeHello(1, "p"), LobbyDirection::ToLobby).reason,
            DropReason::BadIdentifier);
  Bytes big(kMaxDatagramBytes + 1, 0);
  EXPECT_EQ(verifyLobbyDatagram(big, LobbyDirection::ToLobby).reason, DropReason::TooLarge);
  // A grant without a token or a gateway is no grant.
  LoginGrant no_token{9, 1, 3, {0x0a4d0003, 7777}, 1, {}};
  EXPECT_EQ(verifyLobbyDatagram(encodeLoginGranted(no_token), LobbyDirection::ToPlayer).reason,
            DropReason::OutOfRange);
  std::vector<std::uint8_t> token(57, 1);
  LoginGrant no_port{9, 1, 3, {0x0a4d0003, 0}, 1, token};
  EXPECT_EQ(verifyLobbyDatagram(encodeLoginGranted(no_port), LobbyDirection::ToPlayer).reason,
            DropReason::OutOfRange);
}

}  // namespace
}  // namespace zonesim::gateway
