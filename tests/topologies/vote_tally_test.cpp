#include "topologies/vote_tally.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace zonesim::topo {
namespace {

constexpr std::uint32_t kPlayers = 16;
constexpr std::uint64_t kTtl = 30;

Suspects all(std::uint32_t players) {
  return suspectBit(players) - 1;
}

TEST(VoteTally, AMajorityOfTheOthersExcludesAndNoFewer) {
  VoteTally tally(kPlayers, kTtl);
  EXPECT_EQ(tally.needed(), 8u);  // more than half of the 15 others
  for (std::uint32_t voter = 0; voter < 7; ++voter) tally.record({voter, 100, suspectBit(13)});
  EXPECT_EQ(tally.votesAgainst(13, 100), 7u);
  EXPECT_FALSE(tally.excluded(13, 100));
  tally.record({7, 100, suspectBit(13)});
  EXPECT_TRUE(tally.excluded(13, 100));
  // Nobody else is touched.
  for (std::uint32_t p = 0; p < kPlayers; ++p) {
    if (p == 13) continue;
    EXPECT_FALSE(tally.excluded(p, 100)) << p;
  }
}

TEST(VoteTally, OneLiarExcludesNoOneEvenVotingAgainstEveryone) {
  VoteTally tally(kPlayers, kTtl);
  tally.record({12, 50, all(kPlayers) & ~suspectBit(12)});
  for (std::uint32_t voter = 0; voter < kPlayers; ++voter)
    if (voter != 12) tally.record({voter, 50, 0});  // the honest see nothing wrong
  for (std::uint32_t p = 0; p < kPlayers; ++p) {
    EXPECT_FALSE(tally.excluded(p, 50)) << p;
    EXPECT_EQ(tally.votesAgainst(p, 50), p == 12 ? 0u : 1u) << p;
  }
  // Nor do seven liars together: the majority is of the game, not of the voters heard.
  VoteTally seven(kPlayers, kTtl);
  for (std::uint32_t liar = 9; liar < kPlayers; ++liar)
    seven.record({liar, 50, all(kPlayers) & ~suspectBit(liar)});
  for (std::uint32_t p = 0; p < 9; ++p) EXPECT_FALSE(seven.excluded(p, 50)) << p;
}

TEST(VoteTally, APlayerCannotVoteForOrAgainstItselfInTheCount) {
  VoteTally tally(3, kTtl);
  EXPECT_EQ(tally.needed(), 2u);  // both others
  tally.record({0, 1, suspectBit(1) | suspectBit(0)});
  tally.record({1, 1, suspectBit(1)});
  EXPECT_EQ(tally.votesAgainst(1, 1), 1u);
  EXPECT_FALSE(tally.excluded(1, 1));
  tally.record({2, 1, suspectBit(1)});
  EXPECT_TRUE(tally.excluded(1, 1));
}

TEST(VoteTally, TwoPlayersCannotExcludeEachOther) {
  // The other's vote is one accuser against one accused: no majority to trust either way.
  VoteTally pair(2, kTtl);
  EXPECT_EQ(pair.needed(), 2u);
  pair.record({0, 5, suspectBit(1)});
  pair.record({1, 5, suspectBit(0)});
  EXPECT_EQ(pair.votesAgainst(1, 5), 1u);
  EXPECT_FALSE(pair.excluded(0, 5));
  EXPECT_FALSE(pair.excluded(1, 5));
  VoteTally alone(1, kTtl);
  alone.record({0, 5, suspectBit(0)});
  EXPECT_FALSE(alone.excluded(0, 5));
}

TEST(VoteTally, VotesLapseAndNewerOnesReplaceOlder) {
  VoteTally tally(kPlayers, kTtl);
  for (std::uint32_t voter = 0; voter < 8; ++voter) tally.record({voter, 100, suspectBit(15)});
  EXPECT_TRUE(tally.excluded(15, 100 + kTtl));
  EXPECT_FALSE(tally.excluded(15, 101 + kTtl));  // nobody repeated it: the verdicts lapse
  // A withdrawal replaces the vote at once; an older vote arriving late changes nothing.
  EXPECT_TRUE(tally.record({0, 110, 0}));
  EXPECT_FALSE(tally.record({0, 105, suspectBit(15)}));
  EXPECT_FALSE(tally.record({0, 110, suspectBit(15)}));
  EXPECT_EQ(tally.votesAgainst(15, 110), 7u);
  EXPECT_FALSE(tally.excluded(15, 110));
  // A voter that is not in the game is not counted.
  EXPECT_FALSE(tally.record({kPlayers, 120, suspectBit(15)}));
}

TEST(VoteTally, ReadmitsWhenTheMajorityWithdraws) {
  VoteTally tally(kPlayers, kTtl);
  for (std::uint32_t voter = 0; voter < 10; ++voter) tally.record({voter, 10, suspectBit(4)});
  EXPECT_TRUE(tally.excluded(4, 10));
  for (std::uint32_t voter = 0; voter < 3; ++voter) tally.record({voter, 20, 0});
  EXPECT_FALSE(tally.excluded(4, 20));  // 7 of the 8 needed
}

TEST(VoteTally, TheGameSizeIsChecked) {
  EXPECT_THROW(VoteTally(0, kTtl), std::invalid_argument);
  EXPECT_THROW(VoteTally(65, kTtl), std::invalid_argument);
  VoteTally full(64, kTtl);
  EXPECT_EQ(full.needed(), 32u);
  full.record({0, 1, suspectBit(63)});
  EXPECT_EQ(full.votesAgainst(63, 1), 1u);
}

TEST(Verdict, HoldsACaughtPlayerForTheHoldThenForgives) {
  Verdict v(40);
  EXPECT_EQ(v.at(0), 0u);
  v.caught(13, 39);
  v.caught(15, 45);
  EXPECT_EQ(v.at(39), suspectBit(13));
  EXPECT_EQ(v.at(60), suspectBit(13) | suspectBit(15));
  EXPECT_EQ(v.at(78), suspectBit(13) | suspectBit(15));
  EXPECT_EQ(v.at(79), suspectBit(15));  // 40 ticks after its last lie
  v.caught(13, 30);                     // an older catch does not shorten or extend anything
  EXPECT_EQ(v.at(79), suspectBit(15));
  v.caught(13, 80);
  EXPECT_EQ(v.at(85), suspectBit(13));
  EXPECT_EQ(v.at(200), 0u);
}

}  // namespace
}  // namespace zonesim::topo
