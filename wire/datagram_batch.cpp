#include "wire/datagram_batch.h"

#include <algorithm>
#include <cerrno>
#include <system_error>

namespace zonesim::gateway {

namespace {
[[noreturn]] void throwErrno(const char* what) {
  throw std::system_error(errno, std::generic_category(), what);
}
// Not our error: a full buffer, or an ICMP port unreachable of an earlier datagram.
bool droppable(int err) {
  return err == EAGAIN || err == EWOULDBLOCK || err == ECONNREFUSED || err == ENOBUFS;
}
}  // namespace

void SendQueue::push(const Endpoint& to, std::span<const std::uint8_t> bytes) {
  queued_.push_back({to.toSockaddr(), arena_.size(), bytes.size()});
  arena_.insert(arena_.end(), bytes.begin(), bytes.end());
}

FlushResult SendQueue::flush(UdpSocket& socket) {
  FlushResult r;
  // Built after the arena stopped growing, so the pointers into it stay valid.
  headers_.resize(queued_.size());
  iovecs_.resize(queued_.size());
  for (std::size_t i = 0; i < queued_.size(); ++i) {
    Queued& q = queued_[i];
    iovecs_[i] = {arena_.data() + q.offset, q.size};
    msghdr& h = headers_[i].msg_hdr;
    h = {};
    h.msg_name = &q.to;
    h.msg_namelen = sizeof q.to;
    h.msg_iov = &iovecs_[i];
    h.msg_iovlen = 1;
  }
  for (std::size_t at = 0; at < queued_.size();) {
    unsigned n = unsigned(std::min(kBatch, queued_.size() - at));
    int got = ::sendmmsg(socket.fd(), headers_.data() + at, n, 0);
    if (got < 0) {
      if (errno == EINTR) continue;
      if (!droppable(errno)) throwErrno("sendmmsg");
      ++r.failed;  // the first of the batch is refused: drop it, go on with the rest
      ++at;
      continue;
    }
    for (int i = 0; i < got; ++i) r.bytes_sent += queued_[at + std::size_t(i)].size;
    r.sent += std::size_t(got);
    at += std::size_t(got);
  }
  queued_.clear();
  arena_.clear();
  return r;
}

ReceiveBatch::ReceiveBatch(std::size_t buffer_bytes)
    : buffer_bytes_(buffer_bytes),
      stride_((buffer_bytes + 7) / 8 * 8),
      buffers_(stride_ * kBatch),
      from_(kBatch),
      iovecs_(kBatch),
      headers_(kBatch),
      received_(kBatch) {}

std::size_t ReceiveBatch::receive(UdpSocket& socket) {
  for (std::size_t i = 0; i < kBatch; ++i) {
    iovecs_[i] = {buffers_.data() + i * stride_, buffer_bytes_};
    msghdr& h = headers_[i].msg_hdr;
    h = {};
    h.msg_name = &from_[i];
    h.msg_namelen = sizeof from_[i];
    h.msg_iov = &iovecs_[i];
    h.msg_iovlen = 1;
  }
  for (;;) {
    // MSG_TRUNC: msg_len is the datagram's real size, so oversize ones are recognised.
    int got = ::recvmmsg(socket.fd(), headers_.data(), unsigned(kBatch), MSG_TRUNC, nullptr);
    if (got < 0) {
      if (errno == EINTR || errno == ECONNREFUSED) continue;
      if (errno == EAGAIN || errno == EWOULDBLOCK) return 0;
      throwErrno("recvmmsg");
    }
    for (int i = 0; i < got; ++i) {
      Received& r = received_[std::size_t(i)];
      r.size = headers_[std::size_t(i)].msg_len;
      r.truncated =
          r.size > buffer_bytes_ || (headers_[std::size_t(i)].msg_hdr.msg_flags & MSG_TRUNC) != 0;
      r.from = Endpoint::fromSockaddr(from_[std::size_t(i)]);
    }
    return std::size_t(got);
  }
}

std::span<const std::uint8_t> ReceiveBatch::bytes(std::size_t i) const {
  std::size_t n = std::min(received_[i].size, buffer_bytes_);
  return std::span(buffers_.data() + i * stride_, n);
}

}  // namespace zonesim::gateway
