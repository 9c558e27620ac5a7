#pragma once
// Batched system calls for a busy UDP server: datagrams queued during a tick and handed to the
// kernel with sendmmsg, and datagrams taken with recvmmsg, up to kBatch per call. A gateway
// with 1,500 players sends and receives tens of thousands of datagrams a second; one system
// call each was a fixed cost per datagram that batching divides by up to kBatch.

#include <sys/socket.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "wire/udp_socket.h"

namespace zonesim::gateway {

/// What a flush did.
struct FlushResult {
  std::size_t sent = 0, failed = 0;  ///< datagrams the kernel took, and dropped (buffer full)
  std::size_t bytes_sent = 0;
};

/// Datagrams waiting to go out, in order, copied into one arena (no allocation once warm).
class SendQueue {
 public:
  /// Datagrams per sendmmsg call.
  static constexpr std::size_t kBatch = 256;
  /// Queues a copy of bytes for `to`.
  void push(const Endpoint& to, std::span<const std::uint8_t> bytes);
  /// Sends everything queued, in order, and empties the queue. A datagram the kernel refuses
  /// for a full buffer (or an ICMP error of an earlier send) is dropped and counted, as
  /// UdpSocket::sendTo does; other errors throw std::system_error.
  FlushResult flush(UdpSocket& socket);
  std::size_t size() const { return queued_.size(); }
  bool empty() const { return queued_.empty(); }

 private:
  struct Queued {
    sockaddr_in to;
    std::size_t offset, size;
  };
  std::vector<std::uint8_t> arena_;
  std::vector<Queued> queued_;
  std::vector<mmsghdr> headers_;
  std::vector<iovec> iovecs_;
};

/// Buffers for up to kBatch datagrams taken with one recvmmsg call.
class ReceiveBatch {
 public:
  static constexpr std::size_t kBatch = 64;
  /// Each buffer holds buffer_bytes: a datagram that does not fit is reported truncated.
  explicit ReceiveBatch(std::size_t buffer_bytes);
  /// Takes what is pending (up to kBatch); 0 when nothing is. Throws std::system_error on a
  /// socket error (an ICMP error of an earlier send is skipped, as UdpSocket::receive does).
  std::size_t receive(UdpSocket& socket);
  /// Datagram i of the last receive: its bytes (at most the buffer) and what recvmmsg said.
  std::span<const std::uint8_t> bytes(std::size_t i) const;
  const Received& received(std::size_t i) const { return received_[i]; }

 private:
  std::size_t buffer_bytes_;
  std::size_t stride_;  // buffer_bytes_ rounded up to 8: FlatBuffers reads need alignment
  std::vector<std::uint8_t> buffers_;
  std::vector<sockaddr_in> from_;
  std::vector<iovec> iovecs_;
  std::vector<mmsghdr> headers_;
  std::vector<Received> received_;
};

}  // namespace zonesim::gateway
