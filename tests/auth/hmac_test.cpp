// HMAC-SHA-256 against RFC 4231's seven test cases, and the tag comparison.
#include "auth/hmac.h"

#include <gtest/gtest.h>

#include "hex.h"

namespace zonesim::auth {
namespace {

using test::bytesOf;
using test::hex;

std::vector<std::uint8_t> repeated(std::uint8_t b, std::size_t n) {
  return std::vector<std::uint8_t>(n, b);
}

TEST(Hmac, Rfc4231Cases1To4) {
  EXPECT_EQ(hex(hmacSha256(repeated(0x0b, 20), bytesOf("Hi There"))),
            "b0344c61d8db38535ca8afceaf0bf12b881dc200c9833da726e9376c2e32cff7");
  EXPECT_EQ(hex(hmacSha256(bytesOf("Jefe"), bytesOf("what do ya want for nothing?"))),
            "5bdcc146bf60754e6a042426089575c75a003f089d2739839dec58b964ec3843");
  EXPECT_EQ(hex(hmacSha256(repeated(0xaa, 20), repeated(0xdd, 50))),
            "773ea91e36800e46854db8ebd09181a72959098b3ef8c122d9635514ced565fe");
  std::vector<std::uint8_t> key4;
  for (std::uint8_t i = 1; i <= 25; ++i) key4.push_back(i);
  EXPECT_EQ(hex(hmacSha256(key4, repeated(0xcd, 50))),
            "82558a389a443c0ea4cc819899f2083a85f0faa3e578f8077a2e3ff46729665b");
}

TEST(Hmac, Rfc4231Case5Truncated) {
  Digest tag = hmacSha256(repeated(0x0c, 20), bytesOf("Test With Truncation"));
  EXPECT_EQ(hex(std::span(tag).first(16)), "a3b6167473100ee06e0c796c2955552b");
}

// Keys longer than a block are hashed first.
TEST(Hmac, Rfc4231Cases6And7LongKey) {
  EXPECT_EQ(hex(hmacSha256(repeated(0xaa, 131),
                           bytesOf("Test Using Larger Than Block-Size Key - Hash Key First"))),
            "60e431591ee0b67f0d8a26aacbf5b77f8e0bc6213728c5140546040f0ee37f54");
  EXPECT_EQ(hex(hmacSha256(repeated(0xaa, 131),
                           bytesOf("This is a test using a larger than block-size key and a "
                                   "larger than block-size data. The key needs to be hashed "
                                   "before being used by the HMAC algorithm."))),
            "9b09ffa71b942fcb27635fbcd5b0e944bfdc63644f0713938a7f51535c3a35e2");
}

TEST(Hmac, ConstantTimeEqual) {
  std::vector<std::uint8_t> a = repeated(7, 32), b = a;
  EXPECT_TRUE(constantTimeEqual(a, b));
  for (std::size_t i : {0u, 15u, 31u}) {
    b = a;
    b[i] ^= 1;
    EXPECT_FALSE(constantTimeEqual(a, b)) << "differs at " << i;
  }
  EXPECT_FALSE(constantTimeEqual(a, std::span(a).first(31)));
  EXPECT_TRUE(constantTimeEqual({}, {}));
}

}  // namespace
}  // namespace zonesim::auth
