// The gateway's estimate of the zones' clock runs on at the time dilation factor the newest
// sample carries, and ignores factors no zone sends.

#include "gateway/zone_clock.h"

#include <gtest/gtest.h>

#include <limits>

namespace zonesim::gateway {
namespace {

constexpr std::int64_t kMs = 1000000;

TEST(ZoneClock, RunsOnAtFullSpeedWithoutDilation) {
  ZoneClock clock(1.0);
  clock.observe(30, 1.0, 1.0, 0);
  EXPECT_DOUBLE_EQ(clock.simNow(500 * kMs), 1.5);
  EXPECT_EQ(clock.dilation(), 1.0);
}

TEST(ZoneClock, RunsOnAtTheDilatedRate) {
  ZoneClock clock(1.0);
  clock.observe(30, 1.0, 0.3, 0);
  EXPECT_DOUBLE_EQ(clock.simNow(500 * kMs), 1.15);
  EXPECT_EQ(clock.dilation(), 0.3);
  clock.observe(31, 1.1, 1.0, 600 * kMs);  // back to full speed
  EXPECT_DOUBLE_EQ(clock.simNow(800 * kMs), 1.3);
  EXPECT_EQ(clock.minDilation(), 0.3);
}

TEST(ZoneClock, TakesAFactorOutsideZeroToOneForFullSpeed) {
  for (double bad : {0.0, -0.5, 2.0, std::numeric_limits<double>::quiet_NaN()}) {
    ZoneClock clock(1.0);
    clock.observe(30, 1.0, bad, 0);
    EXPECT_EQ(clock.dilation(), 1.0) << bad;
    EXPECT_DOUBLE_EQ(clock.simNow(500 * kMs), 1.5) << bad;
  }
}

}  // namespace
}  // namespace zonesim::gateway
