// Batched sends and receives over real loopback sockets: order, sizes, sources and truncation
// survive, batches larger than one system call's worth go out whole, and an empty socket or
// queue is no error.
#include "wire/datagram_batch.h"

#include <gtest/gtest.h>
#include <poll.h>

#include <vector>

namespace zonesim::gateway {
namespace {

std::vector<std::uint8_t> datagram(std::size_t size, std::uint8_t tag) {
  std::vector<std::uint8_t> d(size);
  for (std::size_t i = 0; i < size; ++i) d[i] = std::uint8_t(tag + i);
  return d;
}

// Everything that reaches `socket` within a second, as (source port, bytes).
std::vector<std::pair<std::uint16_t, std::vector<std::uint8_t>>> drain(UdpSocket& socket,
                                                                        std::size_t expected) {
  ReceiveBatch rx(1400);
  std::vector<std::pair<std::uint16_t, std::vector<std::uint8_t>>> got;
  for (int wait = 0; got.size() < expected && wait < 100; ++wait) {
    pollfd p{socket.fd(), POLLIN, 0};
    ::poll(&p, 1, 10);
    for (std::size_t n = rx.receive(socket), i = 0; i < n; ++i) {
      auto b = rx.bytes(i);
      got.emplace_back(rx.received(i).from.port, std::vector<std::uint8_t>(b.begin(), b.end()));
    }
  }
  return got;
}

TEST(SendQueue, SendsInOrderToEachDestinationAcrossSeveralCalls) {
  UdpSocket sender, a, b;
  SendQueue q;
  // More than one sendmmsg call's worth, alternating destinations and sizes.
  const std::size_t n = SendQueue::kBatch + 50;
  for (std::size_t i = 0; i < n; ++i)
    q.push(Endpoint::loopback((i % 2 ? b : a).localPort()), datagram(20 + i % 300, std::uint8_t(i)));
  EXPECT_EQ(q.size(), n);
  FlushResult r = q.flush(sender);
  EXPECT_EQ(r.sent, n);
  EXPECT_EQ(r.failed, 0u);
  EXPECT_TRUE(q.empty());
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < n; ++i) bytes += 20 + i % 300;
  EXPECT_EQ(r.bytes_sent, bytes);
  auto at_a = drain(a, n / 2 + n % 2), at_b = drain(b, n / 2);
  ASSERT_EQ(at_a.size(), n / 2 + n % 2);
  ASSERT_EQ(at_b.size(), n / 2);
  for (std::size_t k = 0; k < at_a.size(); ++k) {
    EXPECT_EQ(at_a[k].first, sender.localPort());
    EXPECT_EQ(at_a[k].second, datagram(20 + (2 * k) % 300, std::uint8_t(2 * k))) << k;
  }
  for (std::size_t k = 0; k < at_b.size(); ++k)
    EXPECT_EQ(at_b[k].second, datagram(20 + (2 * k + 1) % 300, std::uint8_t(2 * k + 1))) << k;
  // The queue is reusable, and an empty flush sends nothing.
  EXPECT_EQ(q.flush(sender).sent, 0u);
  q.push(Endpoint::loopback(a.localPort()), datagram(5, 9));
  EXPECT_EQ(q.flush(sender).sent, 1u);
  EXPECT_EQ(drain(a, 1).size(), 1u);
}

TEST(ReceiveBatch, ReportsRealSizesOfOversizeDatagramsAndNothingWhenEmpty) {
  UdpSocket sender, receiver;
  ReceiveBatch rx(100);
  EXPECT_EQ(rx.receive(receiver), 0u);
  Endpoint to = Endpoint::loopback(receiver.localPort());
  ASSERT_TRUE(sender.sendTo(to, datagram(60, 1)));
  ASSERT_TRUE(sender.sendTo(to, datagram(300, 2)));
  std::size_t seen = 0;
  for (int wait = 0; seen < 2 && wait < 100; ++wait) {
    pollfd p{receiver.fd(), POLLIN, 0};
    ::poll(&p, 1, 10);
    for (std::size_t n = rx.receive(receiver), i = 0; i < n; ++i, ++seen) {
      const Received& r = rx.received(i);
      EXPECT_EQ(r.from.port, sender.localPort());
      if (seen == 0) {
        EXPECT_EQ(r.size, 60u);
        EXPECT_FALSE(r.truncated);
        EXPECT_EQ(std::vector<std::uint8_t>(rx.bytes(i).begin(), rx.bytes(i).end()),
                  datagram(60, 1));
        // Every buffer starts 8-aligned: FlatBuffers reads 4- and 8-byte fields in place.
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(rx.bytes(i).data()) % 8, 0u);
      } else {
        EXPECT_EQ(r.size, 300u);  // its real size, though only 100 bytes were kept
        EXPECT_TRUE(r.truncated);
        EXPECT_EQ(rx.bytes(i).size(), 100u);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(rx.bytes(i).data()) % 8, 0u);
      }
    }
  }
  EXPECT_EQ(seen, 2u);
}

}  // namespace
}  // namespace zonesim::gateway
