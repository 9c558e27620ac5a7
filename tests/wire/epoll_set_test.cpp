// EpollSet over real loopback sockets: a wait names the ready sockets by their keys, reports a
// socket again while it still holds datagrams (level-triggered), and forgets a removed one.
#include "wire/epoll_set.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <set>
#include <system_error>

#include "common/timer.h"
#include "wire/udp_socket.h"

namespace zonesim::gateway {
namespace {

constexpr std::int64_t kLongWaitNs = 2'000'000'000;  // an upper bound, not a timing claim

std::set<std::uint64_t> readyKeys(EpollSet& set, std::int64_t deadline_ns) {
  std::set<std::uint64_t> keys;
  int n = set.wait(deadline_ns);
  for (int i = 0; i < n; ++i) keys.insert(set.key(i));
  return keys;
}

TEST(EpollSet, NamesReadySocketsByKeyUntilTheyAreRead) {
  UdpSocket a, b, sender;
  EpollSet set;
  set.add(a.fd(), 7);
  set.add(b.fd(), 1'000'000'009);
  EXPECT_TRUE(readyKeys(set, nowNs()).empty());  // nothing sent: the deadline has passed

  const std::array<std::uint8_t, 3> bytes{1, 2, 3};
  ASSERT_TRUE(sender.sendTo(Endpoint::loopback(b.localPort()), bytes));
  EXPECT_EQ(readyKeys(set, nowNs() + kLongWaitNs), (std::set<std::uint64_t>{1'000'000'009}));
  // Not read yet: reported again.
  EXPECT_EQ(readyKeys(set, nowNs() + kLongWaitNs), (std::set<std::uint64_t>{1'000'000'009}));

  std::array<std::uint8_t, 16> buf{};
  ASSERT_TRUE(b.receive(buf));
  EXPECT_TRUE(readyKeys(set, nowNs()).empty());
}

TEST(EpollSet, ForgetsARemovedSocket) {
  UdpSocket a, b, sender;
  EpollSet set;
  set.add(a.fd(), 1);
  set.add(b.fd(), 2);
  set.remove(a.fd());
  const std::array<std::uint8_t, 1> bytes{9};
  ASSERT_TRUE(sender.sendTo(Endpoint::loopback(a.localPort()), bytes));
  ASSERT_TRUE(sender.sendTo(Endpoint::loopback(b.localPort()), bytes));
  EXPECT_EQ(readyKeys(set, nowNs() + kLongWaitNs), (std::set<std::uint64_t>{2}));
  EXPECT_THROW(set.remove(a.fd()), std::system_error);  // not watched any more
}

TEST(TimeoutMsUntil, RoundsUpAndTakesNoDeadline) {
  EXPECT_EQ(timeoutMsUntil(nowNs() - 5), 0);
  // The clock only moves on between the two readings, so rounding up never passes 1000.
  EXPECT_LE(timeoutMsUntil(nowNs() + 1'000'000'000), 1000);
  EXPECT_GT(timeoutMsUntil(INT64_MAX), 0);  // "no deadline" does not overflow into the past
}

}  // namespace
}  // namespace zonesim::gateway
