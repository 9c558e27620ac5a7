// Injected loss, delay and reordering (wire/impairment.h) on real loopback sockets, with
// synthetic clock values: which datagrams go and in what order, never how long it took.
#include "wire/impairment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace zonesim::gateway {
namespace {

std::vector<std::uint32_t> drain(UdpSocket& s) {
  std::vector<std::uint32_t> got;
  std::vector<std::uint8_t> buf(64);
  for (int idle = 0; idle < 200;) {
    auto r = s.receive(buf);
    if (!r) {
      ++idle;
      continue;
    }
    std::uint32_t v;
    std::memcpy(&v, buf.data(), 4);
    got.push_back(v);
  }
  return got;
}

TEST(Impairment, DropsTheSetFractionEachWay) {
  ImpairmentSettings s;
  s.loss = 0.1;
  Impairment imp(s, 3);
  UdpSocket a(0), b(0);
  const int n = 4000;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint8_t bytes[4];
    std::memcpy(bytes, &i, 4);
    ASSERT_TRUE(imp.send(a, Endpoint::loopback(b.localPort()), bytes, 0));
  }
  // Binomial(4000, 0.1): mean 400, sd 19.
  EXPECT_NEAR(double(imp.counters().dropped_out), 400, 80);
  int in = 0;
  for (int i = 0; i < n; ++i) in += imp.dropIncoming();
  EXPECT_NEAR(double(in), 400, 80);
  EXPECT_EQ(imp.counters().dropped_in, std::uint64_t(in));
  ImpairmentSettings off;
  EXPECT_FALSE(off.active());
}

TEST(Impairment, DelayAndJitterHoldThenReorderWithoutLoss) {
  ImpairmentSettings s;
  s.delay_ms = 5;
  s.jitter_ms = 20;
  Impairment imp(s, 4);
  UdpSocket a(0), b(0);
  const std::uint32_t n = 200;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint8_t bytes[4];
    std::memcpy(bytes, &i, 4);
    imp.send(a, Endpoint::loopback(b.localPort()), bytes, std::int64_t(i) * 1'000'000);  // 1 ms
  }
  EXPECT_EQ(imp.counters().delayed, n);
  // Nothing is due before 5 ms; everything by 200 + 25 ms.
  EXPECT_GE(imp.nextDueNs(), 5'000'000);
  EXPECT_EQ(imp.flush(a, 4'999'999), 0);
  EXPECT_TRUE(drain(b).empty());
  imp.flush(a, 226'000'000);
  EXPECT_EQ(imp.nextDueNs(), INT64_MAX);
  std::vector<std::uint32_t> got = drain(b);
  ASSERT_EQ(got.size(), n) << "delay alone loses nothing";
  int inversions = 0;
  for (std::size_t i = 1; i < got.size(); ++i) inversions += got[i] < got[i - 1];
  EXPECT_GT(inversions, 20) << "20 ms of jitter over 1 ms spacing reorders";
  std::vector<std::uint32_t> sorted = got;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < n; ++i) EXPECT_EQ(sorted[i], i);
}

}  // namespace
}  // namespace zonesim::gateway
