#include "topologies/vote_frame.h"

#include <gtest/gtest.h>

#include "topologies/keyed_frame.h"

namespace zonesim::topo {
namespace {

constexpr std::uint64_t kToken = 0x0123456789abcdefull;

TEST(VoteFrame, RoundTrips) {
  for (Vote vote : {Vote{3, 123456, suspectBit(9) | suspectBit(15)}, Vote{0, 0, 0},
                    Vote{63, ~std::uint64_t{0}, ~suspectBit(63)}}) {
    std::vector<std::uint8_t> b = encodeVote(vote, kToken);
    EXPECT_EQ(b[0], kVoteTag);
    ParsedVote p = parseVote(b, kToken);
    ASSERT_FALSE(p.drop) << "voter " << vote.voter;
    EXPECT_EQ(p.vote.voter, vote.voter);
    EXPECT_EQ(p.vote.tick, vote.tick);
    EXPECT_EQ(p.vote.suspects, vote.suspects);
  }
  // 18 bytes for a small tick: tag, voter, one tick byte, the suspects, the checksum.
  EXPECT_EQ(encodeVote({1, 5, 0}, kToken).size(), 18u);
}

TEST(VoteFrame, MalformedAndForgedVotesAreDroppedWithTheirReason) {
  using gateway::DropReason;
  std::vector<std::uint8_t> b = encodeVote({3, 77, suspectBit(9)}, kToken);
  // Not made with the game's token: forged, or for another game.
  EXPECT_EQ(parseVote(b, kToken ^ 1).drop, DropReason::BadChecksum);
  for (std::size_t n = 0; n < b.size(); ++n)
    EXPECT_TRUE(parseVote(std::span(b).first(n), kToken).drop) << "truncated to " << n;
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<std::uint8_t> flipped = b;
      flipped[i] ^= std::uint8_t(1 << bit);
      EXPECT_TRUE(parseVote(flipped, kToken).drop) << "byte " << i << " bit " << bit;
    }
  }
  std::vector<std::uint8_t> hit = b;
  hit[0] = 0xC1;
  EXPECT_EQ(parseVote(hit, kToken).drop, DropReason::BadIdentifier);
  std::vector<std::uint8_t> huge(gateway::kMaxDatagramBytes + 1, kVoteTag);
  EXPECT_EQ(parseVote(huge, kToken).drop, DropReason::TooLarge);
  // Against itself, or from a voter no game has.
  EXPECT_EQ(parseVote(encodeVote({4, 1, suspectBit(4)}, kToken), kToken).drop,
            DropReason::OutOfRange);
  EXPECT_EQ(parseVote(encodeVote({64, 1, 0}, kToken), kToken).drop, DropReason::OutOfRange);
}

TEST(VoteFrame, AWrongLayoutUnderAValidChecksumIsMalformed) {
  // A sender with the token can still get the layout wrong: the checksum passes, the length not
  // (a 3-byte tick, so that a byte short is still long enough to be read).
  std::vector<std::uint8_t> b = encodeVote({3, 1u << 20, 0}, kToken);
  std::vector<std::uint8_t> longer(b.begin(), b.end() - 4), shorter(b.begin(), b.end() - 5);
  longer.push_back(0);
  for (std::vector<std::uint8_t>* body : {&longer, &shorter}) {
    frame::appendKeyedCrc(*body, kToken);
    EXPECT_EQ(parseVote(*body, kToken).drop, gateway::DropReason::Malformed) << body->size();
  }
}

}  // namespace
}  // namespace zonesim::topo
