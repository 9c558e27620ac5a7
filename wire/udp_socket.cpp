#include "wire/udp_socket.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <ifaddrs.h>
#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "common/timer.h"

namespace zonesim::gateway {

namespace {
[[noreturn]] void throwErrno(const char* what) {
  throw std::system_error(errno, std::generic_category(), what);
}
// Many players share one gateway socket: a larger receive buffer absorbs bursts between ticks.
constexpr int kSocketBufferBytes = 4 << 20;
}  // namespace

std::string Endpoint::str() const {
  char buf[INET_ADDRSTRLEN] = {};
  in_addr a{htonl(address)};
  inet_ntop(AF_INET, &a, buf, sizeof buf);
  return std::string(buf) + ":" + std::to_string(port);
}

sockaddr_in Endpoint::toSockaddr() const {
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_addr.s_addr = htonl(address);
  sa.sin_port = htons(port);
  return sa;
}

Endpoint Endpoint::fromSockaddr(const sockaddr_in& sa) {
  return {ntohl(sa.sin_addr.s_addr), ntohs(sa.sin_port)};
}

Endpoint Endpoint::loopback(std::uint16_t port) {
  return {INADDR_LOOPBACK, port};
}

Endpoint Endpoint::any(std::uint16_t port) {
  return {INADDR_ANY, port};
}

namespace {

struct HostPort {
  std::string host;
  std::optional<std::uint16_t> port;
};

// "HOST:PORT" or, where the port may be left out, "HOST". Ports are plain decimal digits.
HostPort splitHostPort(const std::string& text, bool port_required, int min_port) {
  auto colon = text.rfind(':');
  if (colon == std::string::npos) {
    if (port_required) throw std::invalid_argument("expected HOST:PORT, got '" + text + "'");
    return {text, std::nullopt};
  }
  HostPort hp{text.substr(0, colon), std::nullopt};
  std::string port_text = text.substr(colon + 1);
  bool digits = !port_text.empty() && port_text.size() <= 5 &&
                std::all_of(port_text.begin(), port_text.end(),
                            [](char c) { return c >= '0' && c <= '9'; });
  unsigned long port = digits ? std::stoul(port_text) : 0;
  if (!digits || port < unsigned(min_port) || port > 65535)
    throw std::invalid_argument("bad port '" + port_text + "' in '" + text + "' (expected " +
                                std::to_string(min_port) + "-65535)");
  hp.port = std::uint16_t(port);
  return hp;
}

std::optional<std::uint32_t> numericAddress(const std::string& host) {
  in_addr a{};
  if (inet_pton(AF_INET, host.c_str(), &a) != 1) return std::nullopt;
  return ntohl(a.s_addr);
}

// The first IPv4 address of the interface with this name, if there is one.
std::optional<std::uint32_t> interfaceAddress(const std::string& name) {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return std::nullopt;
  std::optional<std::uint32_t> found;
  for (ifaddrs* i = list; i != nullptr && !found; i = i->ifa_next)
    if (i->ifa_addr != nullptr && i->ifa_addr->sa_family == AF_INET && name == i->ifa_name)
      found = ntohl(reinterpret_cast<const sockaddr_in*>(i->ifa_addr)->sin_addr.s_addr);
  freeifaddrs(list);
  return found;
}

std::uint32_t resolvedAddress(const std::string& host) {
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* result = nullptr;
  int rc = getaddrinfo(host.c_str(), nullptr, &hints, &result);
  if (rc != 0 || result == nullptr)
    throw std::invalid_argument("cannot resolve host '" + host +
                                "' to an IPv4 address: " + gai_strerror(rc));
  std::uint32_t address = ntohl(reinterpret_cast<const sockaddr_in*>(result->ai_addr)->sin_addr.s_addr);
  freeaddrinfo(result);
  return address;
}

}  // namespace

Endpoint resolveEndpoint(const std::string& text) {
  HostPort hp = splitHostPort(text, true, 1);
  if (hp.host.empty()) throw std::invalid_argument("no host in '" + text + "'");
  std::optional<std::uint32_t> numeric = numericAddress(hp.host);
  return {numeric ? *numeric : resolvedAddress(hp.host), *hp.port};
}

Endpoint parseBindAddress(const std::string& text, std::uint16_t default_port) {
  HostPort hp = splitHostPort(text, false, 0);
  if (hp.host.empty()) throw std::invalid_argument("no address in '" + text + "'");
  std::uint16_t port = hp.port.value_or(default_port);
  if (auto numeric = numericAddress(hp.host)) return {*numeric, port};
  if (auto local = interfaceAddress(hp.host)) return {*local, port};
  return {resolvedAddress(hp.host), port};
}

BindError::BindError(int err, const Endpoint& where)
    : std::system_error(err, std::generic_category(), "cannot bind " + where.str()),
      where_(where) {}

UdpSocket::UdpSocket(std::uint16_t port) : UdpSocket(Endpoint::loopback(port)) {}

UdpSocket::UdpSocket(const Endpoint& local) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throwErrno("socket");
  int size = kSocketBufferBytes;
  // Best effort: the kernel caps these at rmem_max/wmem_max, which is fine.
  ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
  ::setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &size, sizeof size);
  sockaddr_in sa = local.toSockaddr();
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&sa), sizeof sa) != 0) {
    int err = errno;
    close();
    throw BindError(err, local);
  }
  socklen_t len = sizeof sa;
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len) != 0) {
    int err = errno;
    close();
    throw std::system_error(err, std::generic_category(), "getsockname");
  }
  local_ = Endpoint::fromSockaddr(sa);
}

UdpSocket::~UdpSocket() {
  close();
}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), local_(std::exchange(other.local_, Endpoint{})) {}

UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = std::exchange(other.fd_, -1);
    local_ = std::exchange(other.local_, Endpoint{});
  }
  return *this;
}

void UdpSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

int timeoutMsUntil(std::int64_t deadline_ns) {
  std::int64_t now = nowNs();
  if (deadline_ns <= now) return 0;
  std::int64_t wait_ns = deadline_ns - now;
  // Rounded up without adding first: deadline_ns may be INT64_MAX ("no deadline").
  std::int64_t ms = wait_ns / 1'000'000 + (wait_ns % 1'000'000 != 0 ? 1 : 0);
  return int(std::min<std::int64_t>(ms, INT_MAX));
}

int pollUntil(std::span<pollfd> fds, std::int64_t deadline_ns) {
  int r = ::poll(fds.data(), nfds_t(fds.size()), timeoutMsUntil(deadline_ns));
  if (r < 0 && errno != EINTR) throw std::system_error(errno, std::generic_category(), "poll");
  return r < 0 ? 0 : r;
}

std::string bindOptionText(const std::string& bind_text, int port) {
  return "--bind " + bind_text + (port >= 0 ? " --port " + std::to_string(port) : "");
}

Endpoint bindFromOptions(const std::string& bind_text, int port) {
  if (port >= 0 && bind_text.find(':') != std::string::npos)
    throw std::runtime_error(bindOptionText(bind_text, port) +
                             ": the port is given twice; use one of them");
  try {
    return parseBindAddress(bind_text, std::uint16_t(std::max(port, 0)));
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(bindOptionText(bind_text, port) + ": " + e.what());
  }
}

bool UdpSocket::sendTo(const Endpoint& to, std::span<const std::uint8_t> bytes) {
  sockaddr_in sa = to.toSockaddr();
  for (;;) {
    ssize_t n =
        ::sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&sa), sizeof sa);
    if (n >= 0) return true;
    if (errno == EINTR) continue;
    // A full buffer or a peer that went away (ICMP port unreachable) is not our error.
    if (errno == EAGAIN || errno == EWOULDBLOCK || errno == ECONNREFUSED || errno == ENOBUFS)
      return false;
    throwErrno("sendto");
  }
}

std::optional<Received> UdpSocket::receive(std::span<std::uint8_t> buf) {
  for (;;) {
    sockaddr_in sa{};
    socklen_t len = sizeof sa;
    // MSG_TRUNC reports the datagram's real size, so oversize datagrams are recognised as such.
    ssize_t n =
        ::recvfrom(fd_, buf.data(), buf.size(), MSG_TRUNC, reinterpret_cast<sockaddr*>(&sa), &len);
    if (n >= 0) {
      Received r;
      r.size = std::size_t(n);
      r.truncated = r.size > buf.size();
      r.from = Endpoint::fromSockaddr(sa);
      return r;
    }
    if (errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return std::nullopt;
    // An ICMP error from an earlier send surfaces here; it says nothing about this datagram.
    if (errno == ECONNREFUSED) continue;
    throwErrno("recvfrom");
  }
}

}  // namespace zonesim::gateway
