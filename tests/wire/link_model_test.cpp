// Each impairment model's statistics against its parameters (wire/link_model.h), with fixed
// seeds and tolerances of four standard errors for the sample size, so a correct model fails
// about once in 16,000 runs of a seed and a wrong one by many errors.
#include "wire/link_model.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace zonesim::gateway {
namespace {

constexpr double kSigmas = 4;
constexpr std::int64_t kSecond = 1'000'000'000;

// The sample p-quantile (nearest rank).
double quantile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(p * double(v.size())))];
}

// The standard error of a sample p-quantile of n draws, given the density at the quantile.
double quantileError(double p, std::size_t n, double density) {
  return std::sqrt(p * (1 - p) / double(n)) / density;
}

// Delays (ms) of n datagrams offered a second apart, so the FIFO floor never binds.
std::vector<double> delays(LinkModel& m, std::size_t n) {
  std::vector<double> d;
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t t = std::int64_t(i) * kSecond;
    Fate f = m.offer(100, t);
    EXPECT_EQ(f.copies, 1);
    d.push_back(double(f.delivery[0].due_ns - t) * 1e-6);
  }
  return d;
}

TEST(LinkModel, GilbertElliottLossRateAndMeanBurstLength) {
  LinkProfile p;
  p.ge_p = 0.02;
  p.ge_r = 0.25;
  LinkModel m(p, 11, 1);
  const std::size_t n = 400'000;
  std::size_t lost = 0, bursts = 0, run = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (m.offer(100, 0).copies == 0) {
      ++lost;
      ++run;
    } else if (run > 0) {
      ++bursts;
      run = 0;
    }
  }
  EXPECT_EQ(m.counters().lost, lost);
  double pi_bad = p.ge_p / (p.ge_p + p.ge_r);
  EXPECT_DOUBLE_EQ(p.meanLoss(), pi_bad);
  // A two-state chain's samples are correlated: the variance of the mean grows by
  // (1 + l) / (1 - l), l = 1 - p - r its second eigenvalue.
  double l = 1 - p.ge_p - p.ge_r;
  double rate_error = std::sqrt(pi_bad * (1 - pi_bad) / double(n) * (1 + l) / (1 - l));
  EXPECT_NEAR(double(lost) / double(n), pi_bad, kSigmas * rate_error);
  // Bad sojourns are geometric with mean 1/r and variance (1 - r) / r^2.
  double burst = double(lost) / double(bursts);
  double burst_error = std::sqrt((1 - p.ge_r) / (p.ge_r * p.ge_r) / double(bursts));
  EXPECT_NEAR(burst, 1 / p.ge_r, kSigmas * burst_error);
}

TEST(LinkModel, GilbertElliottWithLossInBothStates) {
  LinkProfile p;
  p.ge_p = 0.05;
  p.ge_r = 0.2;
  p.loss_good = 0.01;
  p.loss_bad = 0.5;
  LinkModel m(p, 12, 1);
  const std::size_t n = 400'000;
  std::size_t lost = 0;
  for (std::size_t i = 0; i < n; ++i) lost += m.offer(100, 0).copies == 0;
  double expect = (0.2 * 0.01 + 0.05 * 0.5) / 0.25;
  EXPECT_DOUBLE_EQ(p.meanLoss(), expect);
  // Bounded by the chain's correlation as above, with the state's variance as the worst case.
  double l = 1 - p.ge_p - p.ge_r;
  double error = std::sqrt(expect * (1 - expect) / double(n) * (1 + l) / (1 - l));
  EXPECT_NEAR(double(lost) / double(n), expect, kSigmas * error);
}

TEST(LinkModel, NormalDelayPercentiles) {
  LinkProfile p;
  p.delay_ms = 50;
  p.jitter = JitterShape::Normal;
  p.jitter_ms = 10;
  LinkModel m(p, 13, 1);
  const std::size_t n = 40'000;
  std::vector<double> d = delays(m, n);
  const double sigma = p.jitter_ms, z99 = 2.326347874;
  auto density = [&](double z) { return std::exp(-z * z / 2) / (sigma * std::sqrt(2 * M_PI)); };
  EXPECT_NEAR(quantile(d, 0.5), 50, kSigmas * quantileError(0.5, n, density(0)));
  EXPECT_NEAR(quantile(d, 0.99), 50 + z99 * sigma, kSigmas * quantileError(0.99, n, density(z99)));
}

TEST(LinkModel, NormalDelayIsTruncatedAtZero) {
  LinkProfile p;
  p.delay_ms = 5;
  p.jitter = JitterShape::Normal;
  p.jitter_ms = 10;
  LinkModel m(p, 14, 1);
  const std::size_t n = 40'000;
  std::vector<double> d = delays(m, n);
  EXPECT_GE(*std::min_element(d.begin(), d.end()), 0);
  double at_zero = double(std::count(d.begin(), d.end(), 0.0)) / double(n);
  double expect = 0.5 * std::erfc(0.5 / std::sqrt(2.0));  // P(N(5, 10) < 0) = Phi(-0.5)
  EXPECT_NEAR(at_zero, expect, kSigmas * std::sqrt(expect * (1 - expect) / double(n)));
}

TEST(LinkModel, ParetoDelayPercentilesAndMean) {
  LinkProfile p;
  p.delay_ms = 20;
  p.jitter = JitterShape::Pareto;
  p.jitter_ms = 10;  // the tail's mean
  p.pareto_shape = 2.5;
  LinkModel m(p, 15, 1);
  const std::size_t n = 100'000;
  std::vector<double> d = delays(m, n);
  const double a = p.pareto_shape, scale = p.jitter_ms * (a - 1);
  // Lomax: Q(q) = scale ((1 - q)^(-1/a) - 1), density there (a / scale) (1 - q)^((a + 1) / a).
  auto q = [&](double x) { return p.delay_ms + scale * (std::pow(1 - x, -1 / a) - 1); };
  auto density = [&](double x) { return a / scale * std::pow(1 - x, (a + 1) / a); };
  for (double x : {0.5, 0.9, 0.99})
    EXPECT_NEAR(quantile(d, x), q(x), kSigmas * quantileError(x, n, density(x))) << "q" << x;
  double mean = 0;
  for (double v : d) mean += v / double(n);
  double variance = scale * scale * a / ((a - 1) * (a - 1) * (a - 2));
  EXPECT_NEAR(mean, p.delay_ms + p.jitter_ms, kSigmas * std::sqrt(variance / double(n)));
}

TEST(LinkModel, CapThroughputEqualsTheRateAndTheQueueBoundsTheDelay) {
  LinkProfile p;
  p.rate_kbps = 1000;
  p.queue_bytes = 20'000;
  LinkModel m(p, 16, 1);
  // 1000-byte datagrams every 4 ms: 2 Mbit/s offered to a 1 Mbit/s link for 20 s.
  std::int64_t first = INT64_MAX, last = 0;
  std::uint64_t bytes = 0;
  double worst_ms = 0;
  for (std::int64_t t = 0; t < 20 * kSecond; t += 4'000'000) {
    Fate f = m.offer(1000, t);
    if (f.copies == 0) continue;
    first = std::min(first, t);
    last = std::max(last, f.delivery[0].due_ns);
    bytes += 1000;
    worst_ms = std::max(worst_ms, double(f.delivery[0].due_ns - t) * 1e-6);
  }
  double kbps = double(bytes) * 8 / (double(last - first) * 1e-9) / 1000;
  EXPECT_NEAR(kbps, 1000, 10) << "the link is busy from the first datagram to the last";
  EXPECT_NEAR(double(m.counters().tail_dropped) / double(m.counters().offered), 0.5, 0.01);
  EXPECT_LE(worst_ms, p.queue_bytes * 8.0 / p.rate_kbps) << "queue_bytes at the rate, at most";
  EXPECT_GT(worst_ms, 0.9 * p.queue_bytes * 8.0 / p.rate_kbps) << "the queue fills";
}

TEST(LinkModel, UnderTheCapNothingIsDroppedAndEachWaitsItsSerialisation) {
  LinkProfile p;
  p.rate_kbps = 1000;
  p.queue_bytes = 2000;
  LinkModel m(p, 17, 1);
  for (std::int64_t t = 0; t < kSecond; t += 16'000'000) {  // 0.5 Mbit/s
    Fate f = m.offer(1000, t);
    ASSERT_EQ(f.copies, 1);
    EXPECT_EQ(f.delivery[0].due_ns - t, 8'000'000) << "1000 bytes at 1 Mbit/s";
  }
}

TEST(LinkModel, ReorderedFractionArrivesAfterItsSuccessor) {
  LinkProfile p;
  p.delay_ms = 10;
  p.reorder = 0.05;
  p.reorder_gap_ms = 25;
  LinkModel m(p, 18, 1);
  const std::size_t n = 50'000;
  std::vector<std::int64_t> due;
  for (std::size_t i = 0; i < n; ++i)
    due.push_back(m.offer(100, std::int64_t(i) * 10'000'000).delivery[0].due_ns);
  std::size_t overtaken = 0;
  for (std::size_t i = 0; i + 1 < n; ++i) overtaken += due[i] > due[i + 1];
  double sd = std::sqrt(p.reorder * (1 - p.reorder) / double(n));
  EXPECT_NEAR(double(m.counters().reordered) / double(n), p.reorder, kSigmas * sd);
  // A 25 ms gap over 10 ms spacing: each held one is overtaken by the next, unless it too
  // was held (probability 0.05).
  EXPECT_NEAR(double(overtaken) / double(n), p.reorder * (1 - p.reorder), kSigmas * sd);
}

TEST(LinkModel, DuplicatedAndCorruptedFractions) {
  LinkProfile p;
  p.duplicate = 0.03;
  p.corrupt = 0.02;
  LinkModel m(p, 19, 1);
  const std::size_t n = 100'000;
  std::size_t twice = 0, flipped = 0, copies = 0;
  for (std::size_t i = 0; i < n; ++i) {
    Fate f = m.offer(40, 0);
    twice += f.copies == 2;
    for (int c = 0; c < f.copies; ++c) {
      std::int64_t bit = f.delivery[std::size_t(c)].flip_bit;
      ASSERT_LT(bit, 40 * 8);
      flipped += bit >= 0;
      ++copies;
    }
  }
  EXPECT_EQ(m.counters().duplicated, twice);
  EXPECT_EQ(m.counters().corrupted, flipped);
  EXPECT_EQ(m.counters().delivered, copies);
  EXPECT_NEAR(double(twice) / double(n), 0.03, kSigmas * std::sqrt(0.03 * 0.97 / double(n)));
  EXPECT_NEAR(double(flipped) / double(copies), 0.02,
              kSigmas * std::sqrt(0.02 * 0.98 / double(copies)));
}

TEST(LinkModel, TheSameSeedGivesTheSameFates) {
  LinkProfile p = *linkPreset("congested");
  LinkModel a(p, 20, 3), b(p, 20, 3), c(p, 20, 4);
  int differ = 0;
  for (std::int64_t i = 0; i < 2000; ++i) {
    std::int64_t t = i * 100'000'000;  // 40 kbit/s: under the cap, so the jitter shows
    Fate fa = a.offer(500, t), fb = b.offer(500, t), fc = c.offer(500, t);
    ASSERT_EQ(fa.copies, fb.copies);
    for (int k = 0; k < fa.copies; ++k) {
      EXPECT_EQ(fa.delivery[std::size_t(k)].due_ns, fb.delivery[std::size_t(k)].due_ns);
      EXPECT_EQ(fa.delivery[std::size_t(k)].flip_bit, fb.delivery[std::size_t(k)].flip_bit);
    }
    differ +=
        fa.copies != fc.copies || (fa.copies > 0 && fa.delivery[0].due_ns != fc.delivery[0].due_ns);
  }
  EXPECT_GT(differ, 1000) << "another stream, other fates";
}

}  // namespace
}  // namespace zonesim::gateway
