// Pcg32: reproducible per seed and stream, resumable from its state after a migration, and
// uniform() covers [0, 1) evenly enough for the simulation's random draws.

#include "common/rng.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace zonesim {
namespace {

std::vector<std::uint32_t> draw(Pcg32& g, int n) {
  std::vector<std::uint32_t> out;
  for (int i = 0; i < n; ++i) out.push_back(g.next());
  return out;
}

TEST(Pcg32, SameSeedAndStreamGiveTheSameSequence) {
  Pcg32 a(42, 54), b(42, 54);
  EXPECT_EQ(draw(a, 100), draw(b, 100));
}

TEST(Pcg32, MatchesTheReferenceImplementation) {
  // First outputs of the PCG reference pcg32_srandom_r(42, 54) (pcg32-demo).
  Pcg32 g(42, 54);
  EXPECT_EQ(draw(g, 6), (std::vector<std::uint32_t>{0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293,
                                                    0xbfa4784b, 0xcbed606e}));
}

TEST(Pcg32, DifferentSeedOrStreamGiveDifferentSequences) {
  Pcg32 base(42, 54), other_seed(43, 54), other_stream(42, 55);
  std::vector<std::uint32_t> seq = draw(base, 20);
  EXPECT_NE(draw(other_seed, 20), seq);
  EXPECT_NE(draw(other_stream, 20), seq);
}

TEST(Pcg32, FromStateContinuesTheSequenceExactly) {
  Pcg32 original(7, 1234);
  draw(original, 37);
  Pcg32 resumed = Pcg32::fromState(original.state(), 1234);
  EXPECT_EQ(resumed.state(), original.state());
  EXPECT_EQ(draw(resumed, 200), draw(original, 200));
  EXPECT_EQ(resumed.uniform(), original.uniform());
}

TEST(Pcg32, UniformIsInUnitIntervalWithMeanOneHalf) {
  Pcg32 g(2024, 3);
  const int n = 100000;
  double sum = 0, lo = 1, hi = 0;
  for (int i = 0; i < n; ++i) {
    double u = g.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    lo = std::min(lo, u);
    hi = std::max(hi, u);
  }
  EXPECT_NEAR(sum / n, 0.5, 0.01);
  EXPECT_LT(lo, 0.001);  // both ends of the interval are reached
  EXPECT_GT(hi, 0.999);
}

TEST(Pcg32, UniformRangeStaysInsideIt) {
  Pcg32 g(1, 1);
  for (int i = 0; i < 1000; ++i) {
    double v = g.uniform(-3.0, 5.0);
    ASSERT_GE(v, -3.0);
    ASSERT_LT(v, 5.0);
  }
}

}  // namespace
}  // namespace zonesim
