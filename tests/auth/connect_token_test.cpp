// Connect tokens: a signed token checks Ok and gives back its fields; forgery (any flipped bit,
// another key, a wrong size or version), another gateway, expiry and another address or port
// are each refused with their own reason.
#include "auth/connect_token.h"

#include <gtest/gtest.h>

#include "tests/auth/test_key.h"
#include "tests/auth/token_tampering.h"

namespace zonesim::auth {
namespace {

AuthKey key(std::uint8_t seed) { return testKey(seed); }

constexpr std::uint32_t kAddress = 0x0a4d0003;  // 10.77.0.3
constexpr std::uint16_t kPort = 40001;
constexpr std::uint64_t kNow = 1'800'000'000'000;

ConnectToken token() {
  ConnectToken t;
  t.player_id = 0x1234'0002'0000'0007;
  t.gateway_id = 2;
  t.client_address = kAddress;
  t.client_port = kPort;
  t.expiry_unix_ms = kNow + 30'000;
  return t;
}

TokenCheck check(std::span<const std::uint8_t> b, const AuthKey& k = key(1),
                 std::uint16_t gateway = 2, std::uint32_t address = kAddress,
                 std::uint16_t port = kPort, std::uint64_t now = kNow) {
  return checkToken(b, k, gateway, address, port, now).check;
}

TEST(ConnectToken, SignedTokenChecksOkWithItsFields) {
  TokenBytes b = signToken(token(), key(1));
  EXPECT_EQ(b.size(), kConnectTokenBytes);
  TokenVerdict v = checkToken(b, key(1), 2, kAddress, kPort, kNow);
  EXPECT_EQ(v.check, TokenCheck::Ok);
  EXPECT_EQ(v.token, token());
}

TEST(ConnectToken, EveryFlippedBitIsForged) {
  TokenBytes good = signToken(token(), key(1));
  EXPECT_EQ(firstFlipAccepted(good, [](auto t) { return check(t) == TokenCheck::Forged; }), "");
}

TEST(ConnectToken, AnotherKeyIsForged) {
  TokenBytes b = signToken(token(), key(2));
  EXPECT_EQ(check(b), TokenCheck::Forged);
}

TEST(ConnectToken, WrongSizeOrVersionIsForged) {
  TokenBytes b = signToken(token(), key(1));
  EXPECT_EQ(firstSizeAccepted(b, [](auto t) { return check(t) == TokenCheck::Forged; }), "");
}

// A forged token claims a gateway or an expiry: none of it is believed before the tag.
TEST(ConnectToken, ForgeryIsReportedBeforeAnyField) {
  TokenBytes b = signToken(token(), key(2));
  EXPECT_EQ(check(b, key(1), 9, 1, 1, kNow + 1'000'000), TokenCheck::Forged);
}

TEST(ConnectToken, AnotherGatewayIsRefused) {
  TokenBytes b = signToken(token(), key(1));
  EXPECT_EQ(check(b, key(1), 3), TokenCheck::WrongGateway);
}

TEST(ConnectToken, ExpiredAtItsExpiry) {
  TokenBytes b = signToken(token(), key(1));
  EXPECT_EQ(check(b, key(1), 2, kAddress, kPort, kNow + 29'999), TokenCheck::Ok);
  EXPECT_EQ(check(b, key(1), 2, kAddress, kPort, kNow + 30'000), TokenCheck::Expired);
  EXPECT_EQ(check(b, key(1), 2, kAddress, kPort, kNow + 3'600'000), TokenCheck::Expired);
}

TEST(ConnectToken, AnotherAddressOrPortIsRefused) {
  TokenBytes b = signToken(token(), key(1));
  EXPECT_EQ(check(b, key(1), 2, kAddress + 1, kPort), TokenCheck::WrongAddress);
  EXPECT_EQ(check(b, key(1), 2, kAddress, kPort + 1), TokenCheck::WrongAddress);
}

}  // namespace
}  // namespace zonesim::auth
