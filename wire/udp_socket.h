#pragma once
// A non-blocking IPv4 UDP socket bound to the loopback interface, with the endpoint type used to
// key sessions by source address. Errors are thrown as std::system_error; nothing here exits.

#include <netinet/in.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>

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
  /// Parses "HOST:PORT" where HOST is a dotted IPv4 loopback address or "localhost"; throws
  /// std::invalid_argument otherwise (the simulator only ever talks over loopback).
  static Endpoint parseLoopback(const std::string& text);
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

/// Owns a non-blocking UDP socket on 127.0.0.1.
class UdpSocket {
 public:
  /// Binds 127.0.0.1:port (0 = ephemeral); throws std::system_error on failure.
  explicit UdpSocket(std::uint16_t port = 0);
  ~UdpSocket();
  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;

  int fd() const { return fd_; }
  /// The bound port (useful after binding port 0).
  std::uint16_t localPort() const { return port_; }
  /// Sends one datagram; false if the kernel buffer is full (the datagram is dropped, as UDP
  /// may do anyway); throws on other errors.
  bool sendTo(const Endpoint& to, std::span<const std::uint8_t> bytes);
  /// Receives one datagram into buf; nullopt when nothing is pending.
  std::optional<Received> receive(std::span<std::uint8_t> buf);

 private:
  void close();
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace zonesim::gateway
