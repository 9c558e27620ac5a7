#include "wire/udp_socket.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <stdexcept>
#include <system_error>
#include <utility>

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

Endpoint Endpoint::parseLoopback(const std::string& text) {
  auto colon = text.rfind(':');
  if (colon == std::string::npos)
    throw std::invalid_argument("expected HOST:PORT, got '" + text + "'");
  std::string host = text.substr(0, colon), port_text = text.substr(colon + 1);
  if (host == "localhost") host = "127.0.0.1";
  in_addr a{};
  if (inet_pton(AF_INET, host.c_str(), &a) != 1)
    throw std::invalid_argument("not an IPv4 address: '" + host + "'");
  if ((ntohl(a.s_addr) >> 24) != 127)
    throw std::invalid_argument("only loopback addresses are supported: '" + host + "'");
  std::size_t used = 0;
  unsigned long port = 0;
  try {
    port = std::stoul(port_text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != port_text.size() || port == 0 || port > 65535)
    throw std::invalid_argument("bad port: '" + port_text + "'");
  return {ntohl(a.s_addr), std::uint16_t(port)};
}

UdpSocket::UdpSocket(std::uint16_t port) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throwErrno("socket");
  int size = kSocketBufferBytes;
  // Best effort: the kernel caps these at rmem_max/wmem_max, which is fine.
  ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &size, sizeof size);
  ::setsockopt(fd_, SOL_SOCKET, SO_SNDBUF, &size, sizeof size);
  sockaddr_in sa = Endpoint::loopback(port).toSockaddr();
  if (::bind(fd_, reinterpret_cast<sockaddr*>(&sa), sizeof sa) != 0) {
    int err = errno;
    close();
    throw std::system_error(err, std::generic_category(), "bind 127.0.0.1:" + std::to_string(port));
  }
  socklen_t len = sizeof sa;
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&sa), &len) != 0) {
    int err = errno;
    close();
    throw std::system_error(err, std::generic_category(), "getsockname");
  }
  port_ = ntohs(sa.sin_port);
}

UdpSocket::~UdpSocket() {
  close();
}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)), port_(std::exchange(other.port_, 0)) {}

UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = std::exchange(other.fd_, -1);
    port_ = std::exchange(other.port_, 0);
  }
  return *this;
}

void UdpSocket::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
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
