// percentile(): nearest rank on a known vector, whatever the order of the samples.

#include "common/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace zonesim {
namespace {

TEST(Percentile, NearestRankOnAKnownVector) {
  // 15, 20, 35, 40, 50 is the textbook nearest-rank example.
  std::vector<double> v = {40, 15, 50, 35, 20};
  EXPECT_EQ(percentile(v, 0), 15);
  EXPECT_EQ(percentile(v, 5), 15);
  EXPECT_EQ(percentile(v, 20), 15);
  EXPECT_EQ(percentile(v, 30), 20);
  EXPECT_EQ(percentile(v, 40), 20);
  EXPECT_EQ(percentile(v, 50), 35);
  EXPECT_EQ(percentile(v, 99), 50);
  EXPECT_EQ(percentile(v, 100), 50);
}

TEST(Percentile, EveryWholePercentOfOneToHundred) {
  // With the samples 1..100, the p-th percentile is p itself (p >= 1).
  std::vector<double> v;
  for (int i = 100; i >= 1; --i) v.push_back(i);
  for (int p = 1; p <= 100; ++p) EXPECT_EQ(percentile(v, p), p) << "p = " << p;
  EXPECT_EQ(percentile(v, 99.9), 100);
  EXPECT_EQ(percentile(v, 0.5), 1);
}

TEST(Percentile, EdgeCases) {
  EXPECT_EQ(percentile({}, 50), 0.0);
  EXPECT_EQ(percentile({7}, 0), 7);
  EXPECT_EQ(percentile({7}, 100), 7);
  std::vector<double> v = {3, 1, 2};
  percentile(v, 50);
  EXPECT_EQ(v, (std::vector<double>{3, 1, 2}));  // the caller's samples are not reordered
}

}  // namespace
}  // namespace zonesim
