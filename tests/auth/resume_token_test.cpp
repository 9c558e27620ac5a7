// Resume tokens: a signed token checks Ok and gives back its fields; any flipped bit, another
// key, a wrong size or version and a connect token are forged; expiry and another address or
// port are refused with their own reason; a token checks Ok as often as it is presented.
#include "auth/resume_token.h"

#include <gtest/gtest.h>

#include "auth/connect_token.h"
#include "tests/auth/test_key.h"
#include "tests/auth/token_tampering.h"

namespace zonesim::auth {
namespace {

constexpr std::uint32_t kAddress = 0x0a4d0003;  // 10.77.0.3
constexpr std::uint16_t kPort = 40001;
constexpr std::uint64_t kNow = 1'800'000'000'000;

ResumeToken token() {
  ResumeToken t;
  t.player_id = 0x1234'0002'0000'0007;
  t.kind = 2;
  t.client_address = kAddress;
  t.client_port = kPort;
  t.expiry_unix_ms = kNow + 86'400'000;
  return t;
}

ResumeCheck check(std::span<const std::uint8_t> b, const AuthKey& k = testKey(1),
                  std::uint32_t address = kAddress, std::uint16_t port = kPort,
                  std::uint64_t now = kNow) {
  return checkResume(b, k, address, port, now).check;
}

TEST(ResumeToken, SignedTokenChecksOkWithItsFields) {
  ResumeBytes b = signResume(token(), testKey(1));
  EXPECT_EQ(b.size(), kResumeTokenBytes);
  ResumeVerdict v = checkResume(b, testKey(1), kAddress, kPort, kNow);
  EXPECT_EQ(v.check, ResumeCheck::Ok);
  EXPECT_EQ(v.token, token());
}

// A player may lose several gateways: the same token takes it back each time.
TEST(ResumeToken, ChecksOkEveryTimeItIsPresented) {
  ResumeBytes b = signResume(token(), testKey(1));
  for (int i = 0; i < 3; ++i) EXPECT_EQ(check(b), ResumeCheck::Ok) << "presentation " << i;
}

TEST(ResumeToken, EveryFlippedBitIsForged) {
  ResumeBytes good = signResume(token(), testKey(1));
  EXPECT_EQ(firstFlipAccepted(good, [](auto t) { return check(t) == ResumeCheck::Forged; }), "");
}

TEST(ResumeToken, AnotherKeyIsForged) {
  ResumeBytes b = signResume(token(), testKey(2));
  EXPECT_EQ(check(b), ResumeCheck::Forged);
}

TEST(ResumeToken, WrongSizeIsForged) {
  ResumeBytes b = signResume(token(), testKey(1));
  EXPECT_EQ(firstSizeAccepted(b, [](auto t) { return check(t) == ResumeCheck::Forged; }), "");
}

// A connect token under the same key never passes for a resume token: its length differs.
TEST(ResumeToken, AConnectTokenIsForged) {
  ConnectToken c;
  c.player_id = token().player_id;
  c.gateway_id = 1;
  c.client_address = kAddress;
  c.client_port = kPort;
  c.expiry_unix_ms = kNow + 30'000;
  TokenBytes b = signToken(c, testKey(1));
  EXPECT_EQ(check(b), ResumeCheck::Forged);
}

// A forged token claims an address or an expiry: none of it is believed before the tag.
TEST(ResumeToken, ForgeryIsReportedBeforeAnyField) {
  ResumeBytes b = signResume(token(), testKey(2));
  EXPECT_EQ(check(b, testKey(1), 1, 1, kNow + 100'000'000), ResumeCheck::Forged);
}

TEST(ResumeToken, ExpiredAtItsExpiry) {
  ResumeBytes b = signResume(token(), testKey(1));
  std::uint64_t expiry = token().expiry_unix_ms;
  EXPECT_EQ(check(b, testKey(1), kAddress, kPort, expiry - 1), ResumeCheck::Ok);
  EXPECT_EQ(check(b, testKey(1), kAddress, kPort, expiry), ResumeCheck::Expired);
}

TEST(ResumeToken, AnotherAddressOrPortIsRefused) {
  ResumeBytes b = signResume(token(), testKey(1));
  EXPECT_EQ(check(b, testKey(1), kAddress + 1, kPort), ResumeCheck::WrongAddress);
  EXPECT_EQ(check(b, testKey(1), kAddress, kPort + 1), ResumeCheck::WrongAddress);
}

}  // namespace
}  // namespace zonesim::auth
