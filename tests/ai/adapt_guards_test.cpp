// The guards hold whatever the model, the measure or a model file throw at them.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "ai/adapt/adapter.h"
#include "ai/adapt/guards.h"
#include "ai/adapt/model_file.h"
#include "ai/parse_error.h"

namespace zonesim::ai::adapt {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Every parameter in its range, and moved at most max_step of its range since `before`.
void expectGuarded(const GuardLimits& g, const NpcParams& before, const NpcParams& after) {
  const std::pair<double NpcParams::*, ParamRange> fields[] = {
      {&NpcParams::accuracy, g.ranges.accuracy},
      {&NpcParams::aggression, g.ranges.aggression},
      {&NpcParams::reaction_steps, g.ranges.reaction_steps}};
  for (auto [field, range] : fields) {
    ASSERT_TRUE(std::isfinite(after.*field));
    EXPECT_TRUE(range.holds(after.*field)) << after.*field;
    EXPECT_LE(std::abs(after.*field - before.*field), g.max_step * (range.hi - range.lo) + 1e-12);
  }
}

TEST(AdaptGuards, AdversarialProposalsStayInRangeAndRateLimited) {
  AdaptGuard guard;
  const GuardLimits& g = guard.limits();
  NpcParams now = g.defaults;
  const double wild[] = {kNaN, kInf, -kInf, 1e300, -1e300, 5.0, -3.0, 0.7, kNaN, 0.2};
  for (double v : wild) {
    const NpcParams next = guard.step(now, {v, v, v});
    expectGuarded(g, now, next);
    now = next;
  }
  // NaN (twice), inf, -inf, +-1e300, 5 and -3 lie beyond the accuracy range by more than its
  // width: 8 fallbacks; 0.7 and 0.2 are clamped.
  EXPECT_EQ(guard.stats().fallbacks, 8u);
  EXPECT_GT(guard.stats().clamped, 0u);
  EXPECT_GT(guard.stats().rate_limited, 0u);
}

TEST(AdaptGuards, FallbackReturnsToDefaultsWithinTheRateLimit) {
  AdaptGuard guard;
  const GuardLimits& g = guard.limits();
  NpcParams now = paramsForDifficulty(1.0);
  for (int i = 0; i < 20; ++i) {
    const NpcParams next = guard.step(now, {kNaN, kNaN, kNaN});
    expectGuarded(g, now, next);
    now = next;
  }
  EXPECT_DOUBLE_EQ(now.accuracy, g.defaults.accuracy);
  EXPECT_DOUBLE_EQ(now.aggression, g.defaults.aggression);
  EXPECT_DOUBLE_EQ(now.reaction_steps, g.defaults.reaction_steps);
  EXPECT_EQ(guard.stats().fallbacks, 20u);
}

TEST(AdaptGuards, CorruptedCurrentStateIsBroughtBack) {
  AdaptGuard guard;
  const NpcParams next = guard.step({kNaN, 1e9, -kInf}, guard.limits().defaults);
  EXPECT_TRUE(guard.limits().ranges.accuracy.holds(next.accuracy));
  EXPECT_TRUE(guard.limits().ranges.aggression.holds(next.aggression));
  EXPECT_TRUE(guard.limits().ranges.reaction_steps.holds(next.reaction_steps));
}

TEST(AdaptGuards, BadLimitsAreRefused) {
  GuardLimits g;
  g.max_step = 0;
  EXPECT_THROW(AdaptGuard{g}, std::invalid_argument);
  g.max_step = kNaN;
  EXPECT_THROW(AdaptGuard{g}, std::invalid_argument);
  g = {};
  g.defaults.accuracy = 2;
  EXPECT_THROW(AdaptGuard{g}, std::invalid_argument);
}

TEST(AdaptGuards, ImpossibleMeasurementsAreRefused) {
  PlayerFeatures f;
  EXPECT_TRUE(f.observeCounts(3, 10));
  const double rate = f.hitRate();
  EXPECT_FALSE(f.observeCounts(kNaN, 10));
  EXPECT_FALSE(f.observeCounts(3, kInf));
  EXPECT_FALSE(f.observeCounts(1e300, 1e300));  // more attacks than a round holds
  EXPECT_FALSE(f.observeCounts(11, 10));
  EXPECT_FALSE(f.observeCounts(-1, 10));
  EXPECT_FALSE(f.observeCounts(0, 0));
  EXPECT_FALSE(f.observe({true, 0, 0, 0}));
  EXPECT_EQ(f.refused(), 7u);
  EXPECT_EQ(f.rounds(), 1u);
  EXPECT_DOUBLE_EQ(f.hitRate(), rate);
}

// A player whose measured performance flips between perfect and hopeless every round: the NPC
// never leaves its ranges nor moves faster than the rate limit, and no fallback is needed.
TEST(AdaptGuards, FlippingPlayerStaysGuarded) {
  DuelModel model;
  std::istringstream in(
      "zonesim-adapt-model 1\nbasis cubic-hd\nweights 1 4 -3 0 0 0 0 0 0 0\nsmoothing 0.5\n");
  model = readModel(in, "flip");
  for (AdaptMode mode : {AdaptMode::Model, AdaptMode::RubberBand}) {
    AdaptSettings s;
    s.mode = mode;
    DuelAdapter a(s, &model);
    NpcParams before = a.params();
    double lowest = 1, highest = 0;
    for (int round = 0; round < 200; ++round) {
      const bool ace = round % 2 == 0;
      a.onRound({ace, 10, ace ? 10 : 0, ace ? 0 : 5});
      expectGuarded(s.guard, before, a.params());
      before = a.params();
      lowest = std::min(lowest, a.params().accuracy);
      highest = std::max(highest, a.params().accuracy);
    }
    EXPECT_EQ(a.guardStats().fallbacks, 0u);
    EXPECT_EQ(a.guardStats().steps, 200u);
    EXPECT_LE(highest - lowest, s.guard.ranges.accuracy.hi - s.guard.ranges.accuracy.lo);
  }
}

// A model file whose weights overflow the logistic: the adapter falls back, never NaN.
TEST(AdaptGuards, OverflowingModelFallsBack) {
  std::istringstream in(
      "zonesim-adapt-model 1\nbasis cubic-hd\n"
      "weights 1e308 1e308 -1e308 1e308 -1e308 1e308 -1e308 1e308 -1e308 1e308\n"
      "smoothing 0.05\n");
  const DuelModel model = readModel(in, "huge");
  AdaptSettings s;
  s.mode = AdaptMode::Model;
  DuelAdapter a(s, &model);
  NpcParams before = a.params();
  for (int round = 0; round < 30; ++round) {
    a.onRound({round % 3 == 0, 12, 5, 3});
    expectGuarded(s.guard, before, a.params());
    before = a.params();
  }
  EXPECT_EQ(a.guardStats().fallbacks, 30u);
}

}  // namespace
}  // namespace zonesim::ai::adapt
