// Link impairment (wire/impairment.h) on real loopback sockets, with synthetic clock values:
// which datagrams go, in what order and intact or not, never how long it took.
#include "wire/impairment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "wire/wire_encode.h"
#include "wire/wire_verify.h"

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
  Impairment imp(injectedImpairment(0.1, 0, 0), 3);
  UdpSocket a(0), b(0);
  const int n = 4000;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint8_t bytes[4];
    std::memcpy(bytes, &i, 4);
    ASSERT_TRUE(imp.send(a, Endpoint::loopback(b.localPort()), bytes, 0));
  }
  // Binomial(4000, 0.1): mean 400, sd 19.
  EXPECT_NEAR(double(imp.counters().out.lost), 400, 80);
  int in = 0;
  for (int i = 0; i < n; ++i) in += imp.dropIncoming();
  EXPECT_NEAR(double(in), 400, 80);
  EXPECT_EQ(imp.counters().in.lost, std::uint64_t(in));
  EXPECT_EQ(imp.nextDueNs(), INT64_MAX) << "loss alone holds nothing back";
  EXPECT_FALSE(ImpairmentSettings{}.active());
}

TEST(Impairment, DelayAndJitterHoldThenReorderWithoutLoss) {
  Impairment imp(injectedImpairment(0, 5, 20), 4);
  UdpSocket a(0), b(0);
  const std::uint32_t n = 200;
  for (std::uint32_t i = 0; i < n; ++i) {
    std::uint8_t bytes[4];
    std::memcpy(bytes, &i, 4);
    imp.send(a, Endpoint::loopback(b.localPort()), bytes, std::int64_t(i) * 1'000'000);  // 1 ms
  }
  EXPECT_EQ(imp.counters().out.delivered, n);
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
  EXPECT_GT(inversions, 20) << "20 ms of jitter that may reorder, over 1 ms spacing, reorders";
  std::vector<std::uint32_t> sorted = got;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < n; ++i) EXPECT_EQ(sorted[i], i);
}

TEST(Impairment, KeepOrderJitterDelaysWithoutReordering) {
  ImpairmentSettings s;
  s.out.jitter = JitterShape::Pareto;
  s.out.jitter_ms = 20;
  s.out.delay_ms = 5;
  Impairment imp(s, 5);
  UdpSocket a(0), b(0);
  for (std::uint32_t i = 0; i < 300; ++i) {
    std::uint8_t bytes[4];
    std::memcpy(bytes, &i, 4);
    imp.send(a, Endpoint::loopback(b.localPort()), bytes, std::int64_t(i) * 1'000'000);
  }
  imp.flush(a, INT64_MAX - 1);
  std::vector<std::uint32_t> got = drain(b);
  ASSERT_EQ(got.size(), 300u);
  EXPECT_TRUE(std::is_sorted(got.begin(), got.end())) << "a FIFO path: jitter does not reorder";
}

TEST(Impairment, EveryCorruptedDatagramFailsTheChecksumAtTheReceiver) {
  ImpairmentSettings s;
  s.out.corrupt = 0.2;
  Impairment imp(s, 6);
  UdpSocket a(0), b(0);
  const int n = 3000;
  DropCounters drops;
  std::uint64_t passed = 0;
  std::vector<std::uint8_t> buf(kMaxDatagramBytes);
  // In batches, so the receiver's socket buffer never overflows.
  for (int batch = 0; batch < n / 100; ++batch) {
    for (int i = batch * 100; i < (batch + 1) * 100; ++i)
      imp.send(a, Endpoint::loopback(b.localPort()), encodeInput(77, std::uint32_t(i + 1), 0.5f, 0),
               i);
    imp.flush(a, n);
    for (int idle = 0; idle < 200;) {
      auto r = b.receive(buf);
      if (!r) {
        ++idle;
        continue;
      }
      Verified v = verifyDatagram(std::span(buf.data(), r->size), Direction::ToGateway);
      if (v.ok())
        ++passed;
      else
        drops.add(v.reason);
    }
  }
  std::uint64_t corrupted = imp.counters().out.corrupted;
  // Binomial(3000, 0.2): sd 22.
  EXPECT_NEAR(double(corrupted), 600, 4 * 22);
  EXPECT_EQ(drops[DropReason::BadChecksum], corrupted) << "CRC-32C catches every 1-bit error";
  EXPECT_EQ(drops.total(), corrupted);
  EXPECT_EQ(passed, n - corrupted);
}

TEST(Impairment, IncomingDatagramsWaitOnTheDownlinkUntilDue) {
  ImpairmentSettings s;
  s.in.delay_ms = 30;
  s.in.duplicate = 1;
  Impairment imp(s, 7);
  const Endpoint from = Endpoint::loopback(9);
  for (std::uint8_t i = 0; i < 10; ++i) {
    std::uint8_t bytes[1] = {i};
    imp.receive(bytes, from, std::int64_t(i) * 1'000'000);
  }
  std::vector<int> got;
  auto handle = [&](std::span<const std::uint8_t> b, const Endpoint& f) {
    EXPECT_EQ(f, from);
    got.push_back(b[0]);
  };
  imp.deliver(29'999'999, handle);
  EXPECT_TRUE(got.empty());
  EXPECT_EQ(imp.nextDueNs(), 30'000'000);
  imp.deliver(34'000'000, handle);
  EXPECT_EQ(got, (std::vector<int>{0, 0, 1, 1, 2, 2, 3, 3, 4, 4}));
  EXPECT_THROW(imp.dropIncoming(), std::logic_error) << "a delaying downlink cannot just drop";
}

TEST(Impairment, EachDestinationHasItsOwnCap) {
  ImpairmentSettings s;
  s.out.rate_kbps = 100;  // 1000 bytes take 80 ms
  s.out.queue_bytes = 1500;
  Impairment imp(s, 8);
  UdpSocket a(0), b(0), c(0);
  std::vector<std::uint8_t> kb(1000);
  for (UdpSocket* to : {&b, &c}) imp.send(a, Endpoint::loopback(to->localPort()), kb, 0);
  EXPECT_EQ(imp.counters().out.tail_dropped, 0u) << "two links, one datagram queued on each";
  imp.send(a, Endpoint::loopback(b.localPort()), kb, 0);
  EXPECT_EQ(imp.counters().out.tail_dropped, 1u) << "a second one does not fit b's queue";
  EXPECT_EQ(imp.nextDueNs(), 80'000'000);
}

}  // namespace
}  // namespace zonesim::gateway
