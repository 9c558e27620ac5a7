// The lobby's directory: the least-loaded live gateway with room is chosen, grants count as load
// until the gateway reports them as logins or they expire, silent gateways are skipped.
#include "lobby/gateway_directory.h"

#include <gtest/gtest.h>

namespace zonesim::lobby {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;
constexpr std::uint64_t kUnixMs = 1'800'000'000'000;

GatewayReport report(std::uint16_t id, std::uint32_t sessions, std::uint64_t logins = 0,
                     std::uint32_t max = 100, std::uint16_t incarnation = 1) {
  GatewayReport r;
  r.gateway_id = id;
  r.incarnation = incarnation;
  r.address = gateway::Endpoint::loopback(std::uint16_t(7000 + id));
  r.sessions = sessions;
  r.max_sessions = max;
  r.logins = logins;
  return r;
}

std::uint16_t picked(GatewayDirectory& d, std::int64_t now = 0, std::uint64_t unix_ms = kUnixMs) {
  const GatewayEntry* e = d.pick(now, unix_ms);
  return e != nullptr ? e->last.gateway_id : 0;
}

TEST(GatewayDirectory, NoReportNoGateway) {
  GatewayDirectory d(3 * kSecond);
  EXPECT_EQ(d.pick(0, kUnixMs), nullptr);
  EXPECT_EQ(d.live(0), 0u);
}

TEST(GatewayDirectory, LeastReportedSessionsWinsTiesToTheLowestId) {
  GatewayDirectory d(3 * kSecond);
  d.report(report(2, 10), 0);
  d.report(report(1, 12), 0);
  d.report(report(3, 10), 0);
  EXPECT_EQ(picked(d), 2);
}

// Between two reports a burst of logins spreads out instead of all landing on one gateway.
TEST(GatewayDirectory, GrantsCountUntilReportedAsLogins) {
  GatewayDirectory d(3 * kSecond);
  d.report(report(1, 0), 0);
  d.report(report(2, 0), 0);
  std::map<std::uint16_t, int> n;
  for (int i = 0; i < 10; ++i) {
    std::uint16_t g = picked(d);
    ++n[g];
    d.granted(g, kUnixMs + 30'000);
  }
  EXPECT_EQ(n[1], 5);
  EXPECT_EQ(n[2], 5);
  // Gateway 1 reports its 5 logins as 5 sessions: its load stays 5, not 10.
  d.report(report(1, 5, 5), kSecond);
  EXPECT_EQ(GatewayDirectory::load(d.entries().at(1)), 5u);
  // Gateway 2 saw only 2 of its players yet: 2 sessions + 3 in flight.
  d.report(report(2, 2, 2), kSecond);
  EXPECT_EQ(GatewayDirectory::load(d.entries().at(2)), 5u);
  EXPECT_EQ(d.entries().at(2).granted, 5u);
}

TEST(GatewayDirectory, ExpiredGrantsStopCounting) {
  GatewayDirectory d(3 * kSecond);
  d.report(report(1, 0), 0);
  d.report(report(2, 1), 0);
  d.granted(1, kUnixMs + 1000);
  d.granted(1, kUnixMs + 1000);
  EXPECT_EQ(picked(d, 0, kUnixMs), 2) << "1 has 2 in flight, 2 has 1 session";
  EXPECT_EQ(picked(d, 0, kUnixMs + 1000), 1) << "the tokens expired unused";
  EXPECT_EQ(GatewayDirectory::load(d.entries().at(1)), 0u);
}

TEST(GatewayDirectory, SilentGatewaysAreSkipped) {
  GatewayDirectory d(3 * kSecond);
  d.report(report(1, 0), 0);
  d.report(report(2, 50), 0);
  d.report(report(2, 50), 3 * kSecond);
  EXPECT_EQ(picked(d, 3 * kSecond), 1);
  EXPECT_EQ(picked(d, 3 * kSecond + 1), 2) << "1 has been silent for over 3 s";
  EXPECT_EQ(d.live(3 * kSecond + 1), 1u);
  EXPECT_EQ(picked(d, 7 * kSecond), 0);
}

TEST(GatewayDirectory, FullGatewaysAreSkipped) {
  GatewayDirectory d(3 * kSecond);
  d.report(report(1, 1, 0, 2), 0);
  d.report(report(2, 5, 0, 6), 0);
  EXPECT_EQ(picked(d), 1);
  d.granted(1, kUnixMs + 30'000);
  EXPECT_EQ(picked(d), 2) << "1 is full with its grant in flight";
  d.report(report(2, 6, 0, 6), 0);
  EXPECT_EQ(picked(d), 0);
}

// A restarted gateway counts logins from 0: its first report settles nothing.
TEST(GatewayDirectory, RestartedGatewayKeepsGrantsInFlight) {
  GatewayDirectory d(3 * kSecond);
  d.report(report(1, 0, 100, 100, 1), 0);
  d.granted(1, kUnixMs + 30'000);
  d.report(report(1, 0, 3, 100, 2), kSecond);
  EXPECT_EQ(d.entries().at(1).in_flight.size(), 1u);
  d.report(report(1, 1, 4, 100, 2), 2 * kSecond);
  EXPECT_EQ(d.entries().at(1).in_flight.size(), 0u);
}

}  // namespace
}  // namespace zonesim::lobby
