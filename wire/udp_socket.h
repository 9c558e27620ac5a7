#pragma once
// A non-blocking IPv4 UDP socket, with the endpoint type used to key sessions by source address
// and the parsing of the addresses users type (IPv4 only: the cluster networks this targets are
// IPv4, and one family keeps the session key a single 48-bit value). Errors are thrown as
// std::invalid_argument (bad text), std::system_error or BindError; nothing here exits.

#include <netinet/in.h>
#include <poll.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <system_error>

namespace zonesim::gateway {

/// An IPv4 address and port, both in host byte order.
struct Endpoint {
  std::uint32_t address = 0;
  std::uint16_t port = 0;
  friend bool operator==(const Endpoint&, const Endpoint&) = default;
  /// "a.b.c.d:port".
  std::string str() const;
  sockaddr_in toSockaddr() const;
  static Endpoint fromSockaddr(const sockaddr_in& sa);
  /// 127.0.0.1:port.
  static Endpoint loopback(std::uint16_t port);
  /// 0.0.0.0:port: every interface (a client's socket, so it reaches any gateway's route).
  static Endpoint any(std::uint16_t port);
};

/// The address to send to from "HOST:PORT": HOST is a dotted IPv4 address or a name resolved
/// with getaddrinfo (IPv4 results only), PORT 1-65535. Throws std::invalid_argument with a
/// message that quotes the text and says what is wrong (no colon, bad port, unknown host).
Endpoint resolveEndpoint(const std::string& text);

/// The address to bind from "ADDR" or "ADDR:PORT" (PORT 0-65535, default_port when absent):
/// ADDR is a dotted IPv4 address (0.0.0.0 = every interface), the name of a local interface
/// (its first IPv4 address) or a host name that resolves to an IPv4 address. Throws
/// std::invalid_argument as resolveEndpoint does; whether the address is local shows at bind.
Endpoint parseBindAddress(const std::string& text, std::uint16_t default_port);

/// How a program's --bind and --port options read as typed (port < 0: --port not given), for
/// errors about them: "--bind ADDR[ --port P]".
std::string bindOptionText(const std::string& bind_text, int port);
/// The address to bind from those options: parseBindAddress(bind_text, port). Throws
/// std::runtime_error starting with bindOptionText when the text is bad or the port is given
/// both ways.
Endpoint bindFromOptions(const std::string& bind_text, int port);

/// A bind that failed (address in use, not a local address, no permission): what() is one line
/// naming the address, e.g. "cannot bind 10.0.0.9:4000: Cannot assign requested address".
class BindError : public std::system_error {
 public:
  BindError(int err, const Endpoint& where);
  const Endpoint& where() const { return where_; }

 private:
  Endpoint where_;
};

/// Hash for unordered containers keyed by endpoint.
struct EndpointHash {
  std::size_t operator()(const Endpoint& e) const {
    return std::hash<std::uint64_t>()((std::uint64_t{e.address} << 16) | e.port);
  }
};

/// One received datagram: its real size (may exceed the buffer: truncated) and its source.
struct Received {
  std::size_t size = 0;
  bool truncated = false;
  Endpoint from;
};

/// The wait from now to deadline_ns on the steady clock (common/timer.h nowNs()) as a poll or
/// epoll_wait timeout: whole milliseconds rounded up, so it never wakes early; 0 when past.
int timeoutMsUntil(std::int64_t deadline_ns);

/// Waits in poll() until one of fds is ready or the steady clock reaches deadline_ns
/// (timeoutMsUntil). Returns poll's count: 0 on timeout or a signal; throws std::system_error
/// on other errors.
int pollUntil(std::span<pollfd> fds, std::int64_t deadline_ns);

/// Owns a non-blocking UDP socket.
class UdpSocket {
 public:
  /// Binds 127.0.0.1:port (0 = ephemeral); throws BindError or std::system_error on failure.
  explicit UdpSocket(std::uint16_t port = 0);
  /// Binds local (port 0 = ephemeral); throws BindError or std::system_error on failure.
  explicit UdpSocket(const Endpoint& local);
  ~UdpSocket();
  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  int fd() const { return fd_; }
  /// The bound port (useful after binding port 0).
  std::uint16_t localPort() const { return local_.port; }
  /// The bound address and port.
  const Endpoint& local() const { return local_; }
  /// Sends one datagram; false if the kernel buffer is full (the datagram is dropped, as UDP
  /// may do anyway); throws on other errors.
  bool sendTo(const Endpoint& to, std::span<const std::uint8_t> bytes);
  /// Receives one datagram into buf; nullopt when nothing is pending.
  std::optional<Received> receive(std::span<std::uint8_t> buf);

 private:
  void close();
  int fd_ = -1;
  Endpoint local_;
};

}  // namespace zonesim::gateway
