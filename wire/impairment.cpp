#include "wire/impairment.h"

#include <climits>

namespace zonesim::gateway {

bool Impairment::send(UdpSocket& socket, const Endpoint& to, std::span<const std::uint8_t> bytes,
                      std::int64_t now_ns) {
  if (s_.loss > 0 && rng_.uniform(0, 1) < s_.loss) {
    ++counters_.dropped_out;
    return true;  // "sent": the network lost it
  }
  double hold_ms = s_.delay_ms + (s_.jitter_ms > 0 ? rng_.uniform(0, s_.jitter_ms) : 0.0);
  if (hold_ms <= 0) return socket.sendTo(to, bytes);
  held_.push({now_ns + std::int64_t(hold_ms * 1e6), order_++, to,
              std::vector<std::uint8_t>(bytes.begin(), bytes.end())});
  ++counters_.delayed;
  return true;
}

bool Impairment::dropIncoming() {
  if (s_.loss > 0 && rng_.uniform(0, 1) < s_.loss) {
    ++counters_.dropped_in;
    return true;
  }
  return false;
}

int Impairment::flush(UdpSocket& socket, std::int64_t now_ns) {
  int refused = 0;
  while (!held_.empty() && held_.top().due_ns <= now_ns) {
    if (!socket.sendTo(held_.top().to, held_.top().bytes)) ++refused;
    held_.pop();
  }
  return refused;
}

std::int64_t Impairment::nextDueNs() const {
  return held_.empty() ? INT64_MAX : held_.top().due_ns;
}

}  // namespace zonesim::gateway
