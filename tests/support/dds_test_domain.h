#pragma once
// A DDS domain private to one test process, for every test that starts DDS participants (C++
// here, Python in tests/integration/harness.py with the same rule and the same lock files).
// Requires ZONESIM_CYCLONEDDS_XML (the loopback config) as a compile definition.

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace zonesim::testing {

namespace detail {
// Cyclone's default port mapping: domain d uses UDP ports 7400 + 250 d + [0, 250), d <= 232.
constexpr int kDdsPortBase = 7400, kDdsDomainGain = 250, kMaxDdsDomain = 232;

// The range bind(port 0) draws from: every UDP socket of the gateway and of the sim players.
inline std::pair<int, int> ephemeralPorts() {
  int lo = 32768, hi = 60999;  // Linux's default
  std::ifstream f("/proc/sys/net/ipv4/ip_local_port_range");
  if (!(f >> lo >> hi)) return {32768, 60999};
  return {lo, hi};
}

// Domains none of whose ports can be handed out as ephemeral ports. With unicast discovery
// (deploy/cyclonedds.xml) every participant sends its SPDP announcements to 127.0.0.1 at the
// discovery port of all 61 participant indices of its domain, whether anything listens there or
// not: a test socket that drew one of those ports receives RTPS datagrams, which the gateway and
// the clients rightly count as drops. Domain 0 is left to hand-started runs.
inline std::vector<int> domainsClearOfEphemeralPorts() {
  auto [lo, hi] = ephemeralPorts();
  std::vector<int> clear;
  for (int d = 1; d <= kMaxDdsDomain; ++d) {
    int first = kDdsPortBase + kDdsDomainGain * d, last = first + kDdsDomainGain - 1;
    if (last < lo || first > hi) clear.push_back(d);
  }
  return clear;
}

// Holds an advisory lock on domain d for the life of the process; false if another holds it.
inline bool lockDomain(int d) {
  std::error_code ec;
  auto dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  auto path = dir / ("zonesim_test_dds_domain_" + std::to_string(d) + ".lock");
  int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
  if (fd < 0) return false;
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return true;  // fd stays open: the lock with it
  ::close(fd);
  return false;
}

inline int pickDdsDomain() {
  std::vector<int> domains = domainsClearOfEphemeralPorts();
  // An ephemeral range that spans every domain: isolation by port is impossible, take any.
  for (int d = 1; domains.empty() && d <= kMaxDdsDomain; ++d) domains.push_back(d);
  auto t = std::chrono::steady_clock::now().time_since_epoch().count();
  std::size_t start = std::size_t((std::uint64_t(getpid()) * 7919 + std::uint64_t(t)) %
                                  std::uint64_t(domains.size()));
  // Two test processes on one domain see each other's samples (and a spawn writer may count
  // the other test's zone as matched): the lock keeps the gateway and clients tests apart.
  for (std::size_t i = 0; i < domains.size(); ++i) {
    int d = domains[(start + i) % domains.size()];
    if (lockDomain(d)) return d;
  }
  return domains[start];
}
}  // namespace detail

/// Points Cyclone at the loopback config and returns a domain that no other gateway or clients
/// test process uses at the same time, whose ports none of the tests' UDP sockets can draw.
inline int privateDdsDomain() {
  setenv("CYCLONEDDS_URI", "file://" ZONESIM_CYCLONEDDS_XML, 1);
  static const int domain = detail::pickDdsDomain();
  return domain;
}

}  // namespace zonesim::testing
