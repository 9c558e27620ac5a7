// The time-dilation controller on synthetic work figures (the slowest rank's seconds per tick):
// steps down to the step that fits, floors at min_factor, steps up one step at a time after
// quiet windows, holds inside the hysteresis band, and is a pure function of its inputs.

#include "zone_node/time_dilation.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "common/rng.h"

namespace zonesim::zone {
namespace {

constexpr double kRate = 30;  // ticks per wall second at full speed
constexpr double kBase = 1.0 / kRate;

TimeDilationSettings settings(int window = 10) {
  TimeDilationSettings s;
  s.enabled = true;
  s.window = window;
  return s;  // min 0.1, step 0.1, slow above 0.9, speed below 0.6, 3 windows to recover
}

// Feeds `ticks` ticks of `work` seconds each, starting at tick *tick.
void feed(TimeDilation& td, double work, int ticks, std::uint64_t& tick) {
  for (int i = 0; i < ticks; ++i) td.record(work, ++tick);
}

TEST(TimeDilation, StaysAtFullSpeedWhileTheWorkFits) {
  TimeDilation td(settings(), kRate);
  std::uint64_t tick = 0;
  feed(td, 0.85 * kBase, 1000, tick);
  EXPECT_EQ(td.factor(), 1.0);
  EXPECT_EQ(td.changes(), 0u);
  EXPECT_DOUBLE_EQ(td.periodSeconds(), kBase);
}

TEST(TimeDilation, DecidesOnlyAtTheEndOfAWindow) {
  TimeDilation td(settings(10), kRate);
  for (std::uint64_t t = 1; t < 10; ++t) EXPECT_FALSE(td.record(50 * kBase, t));
  EXPECT_EQ(td.factor(), 1.0);
  EXPECT_TRUE(td.record(50 * kBase, 10));
  EXPECT_LT(td.factor(), 1.0);
  EXPECT_EQ(td.sinceTick(), 10u);
}

TEST(TimeDilation, StepsDownAtOnceToTheFirstStepWhosePeriodFits) {
  TimeDilation td(settings(), kRate);
  std::uint64_t tick = 0;
  // 2.5 periods of work: 0.9 * kBase / f >= 2.5 * kBase needs f <= 0.36, so 0.3.
  feed(td, 2.5 * kBase, 10, tick);
  EXPECT_NEAR(td.factor(), 0.3, 1e-12);
  EXPECT_EQ(td.changes(), 1u);
  EXPECT_EQ(td.sinceTick(), 10u);
  EXPECT_NEAR(td.periodSeconds(), kBase / 0.3, 1e-12);
  // The same load again fits the dilated period: no further step.
  feed(td, 2.5 * kBase, 100, tick);
  EXPECT_EQ(td.changes(), 1u);
}

TEST(TimeDilation, NeverGoesBelowMinFactor) {
  TimeDilation td(settings(), kRate);
  std::uint64_t tick = 0;
  feed(td, 100 * kBase, 100, tick);
  EXPECT_NEAR(td.factor(), 0.1, 1e-12);
  EXPECT_EQ(td.factorAt(td.lowestLevel()), td.factor());

  // A floor off the ladder is its last step: 1, 0.9, ..., 0.3, then 0.25.
  TimeDilationSettings s = settings();
  s.min_factor = 0.25;
  TimeDilation floored(s, kRate);
  EXPECT_NEAR(floored.factorAt(floored.lowestLevel() - 1), 0.3, 1e-12);
  feed(floored, 100 * kBase, 100, tick);
  EXPECT_EQ(floored.factor(), 0.25);
}

TEST(TimeDilation, StepsUpOneStepPerRecoverWindowsWhenTheLoadFalls) {
  TimeDilation td(settings(), kRate);
  std::uint64_t tick = 0;
  feed(td, 100 * kBase, 10, tick);
  ASSERT_NEAR(td.factor(), 0.1, 1e-12);
  // Light work: each step up waits for 3 quiet windows of 10 ticks.
  feed(td, 0.1 * kBase, 29, tick);
  EXPECT_NEAR(td.factor(), 0.1, 1e-12);
  feed(td, 0.1 * kBase, 1, tick);
  EXPECT_NEAR(td.factor(), 0.2, 1e-12);
  EXPECT_EQ(td.sinceTick(), tick);
  feed(td, 0.1 * kBase, 8 * 30, tick);
  EXPECT_EQ(td.factor(), 1.0);
  EXPECT_EQ(td.changes(), 10u);  // one down, nine up
  feed(td, 0.1 * kBase, 300, tick);
  EXPECT_EQ(td.changes(), 10u);
}

TEST(TimeDilation, HoldsInsideTheHysteresisBand) {
  TimeDilation td(settings(1), kRate);
  std::uint64_t tick = 0;
  // 1.6 periods: 0.9 / f >= 1.6 needs f <= 0.5625, so 0.5.
  feed(td, 1.6 * kBase, 1, tick);
  ASSERT_NEAR(td.factor(), 0.5, 1e-12);
  // At 0.5 the work 1.6 fits under 0.9 * 2 = 1.8 periods; at 0.6 it would not be under
  // 0.6 / 0.6 = 1 period: neither step, whatever the noise inside the band.
  Pcg32 rng(7, 7);
  for (int i = 0; i < 2000; ++i) td.record((1.05 + 0.7 * rng.uniform()) * kBase, ++tick);
  EXPECT_NEAR(td.factor(), 0.5, 1e-12);
  EXPECT_EQ(td.changes(), 1u);
}

TEST(TimeDilation, ALoadedWindowRestartsTheCountTowardsAStepUp) {
  TimeDilation td(settings(1), kRate);
  std::uint64_t tick = 0;
  feed(td, 1.6 * kBase, 1, tick);
  ASSERT_NEAR(td.factor(), 0.5, 1e-12);
  for (int i = 0; i < 100; ++i) {
    feed(td, 0.2 * kBase, 2, tick);  // two quiet windows of the three needed
    feed(td, 1.5 * kBase, 1, tick);  // in the band: not quiet
  }
  EXPECT_NEAR(td.factor(), 0.5, 1e-12);
}

TEST(TimeDilation, EqualInputsGiveEqualFactorsOnEveryRank) {
  // Every rank feeds the same allreduced figures: the controllers must step alike.
  TimeDilation a(settings(), kRate), b(settings(), kRate);
  Pcg32 rng(3, 11);
  std::vector<double> fa, fb;
  for (std::uint64_t t = 1; t <= 5000; ++t) {
    double w = kBase * (t % 1000 < 300 ? 4.0 * rng.uniform() : 0.3 * rng.uniform());
    a.record(w, t);
    b.record(w, t);
    fa.push_back(a.factor());
    fb.push_back(b.factor());
  }
  EXPECT_EQ(fa, fb);
  EXPECT_GT(a.changes(), 2u);  // the load went up and down: the clock followed
}

}  // namespace
}  // namespace zonesim::zone
