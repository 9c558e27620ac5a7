#include "topologies/hit_frame.h"

#include <gtest/gtest.h>

namespace zonesim::topo {
namespace {

constexpr std::uint64_t kToken = 0x0123456789abcdefull;

TEST(HitFrame, RoundTrips) {
  HitClaim hit{3, 9, 123456};
  std::vector<std::uint8_t> b = encodeHit(hit, kToken);
  EXPECT_EQ(b[0], kHitTag);
  ParsedHit p = parseHit(b, kToken);
  ASSERT_FALSE(p.drop);
  EXPECT_EQ(p.hit.attacker, 3u);
  EXPECT_EQ(p.hit.target, 9u);
  EXPECT_EQ(p.hit.tick, 123456u);
}

TEST(HitFrame, MalformedClaimsAreDroppedWithTheirReason) {
  using gateway::DropReason;
  std::vector<std::uint8_t> b = encodeHit({3, 9, 77}, kToken);
  EXPECT_EQ(parseHit(b, kToken ^ 1).drop, DropReason::BadChecksum);
  for (std::size_t n = 0; n < b.size(); ++n)
    EXPECT_TRUE(parseHit(std::span(b).first(n), kToken).drop) << "truncated to " << n;
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<std::uint8_t> flipped = b;
      flipped[i] ^= std::uint8_t(1 << bit);
      EXPECT_TRUE(parseHit(flipped, kToken).drop) << "byte " << i << " bit " << bit;
    }
  }
  std::vector<std::uint8_t> other = b;
  other[0] = 0xA1;
  EXPECT_EQ(parseHit(other, kToken).drop, DropReason::BadIdentifier);
  EXPECT_EQ(parseHit(encodeHit({4, 4, 1}, kToken), kToken).drop, DropReason::OutOfRange);
}

}  // namespace
}  // namespace zonesim::topo
