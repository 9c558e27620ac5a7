#include "topologies/discovery_service.h"

#include <poll.h>

#include <stdexcept>
#include <variant>

#include "common/timer.h"
#include "topologies/discovery_message.h"

namespace zonesim::topo {

std::string DiscoveryService::answer(std::span<const std::uint8_t> request, double now_s) {
  try {
    DiscoveryRequest r =
        parseRequest({reinterpret_cast<const char*>(request.data()), request.size()});
    if (const auto* reg = std::get_if<RegisterRequest>(&r)) {
      registry_.add(reg->registration, now_s, reg->ttl_s);
      ++counters_.registers;
      return "ok";
    }
    ++counters_.lists;
    return formatPeers(registry_.list(now_s));
  } catch (const std::invalid_argument& e) {
    ++counters_.errors;
    return std::string("error ") + e.what();
  }
}

void DiscoveryService::run(const std::atomic<bool>& stop, double duration_s) {
  std::int64_t start = nowNs();
  std::int64_t end = duration_s > 0 ? start + std::int64_t(duration_s * 1e9) : 0;
  std::uint8_t buf[kMaxDiscoveryBytes + 1];
  while (!stop.load()) {
    std::int64_t now = nowNs();
    if (end && now >= end) return;
    // Wake at least every 100 ms to notice the stop flag.
    pollfd fd{socket_.fd(), POLLIN, 0};
    std::int64_t deadline = now + 100'000'000;
    if (end && end < deadline) deadline = end;
    if (gateway::pollUntil({&fd, 1}, deadline) <= 0) continue;
    while (auto r = socket_.receive(buf)) {
      std::string reply = r->truncated ? "error request longer than " +
                                             std::to_string(kMaxDiscoveryBytes) + " bytes"
                                       : answer({buf, r->size}, double(nowNs() - start) * 1e-9);
      if (r->truncated) ++counters_.errors;
      if (reply.size() > kMaxDiscoveryBytes) reply = "error the list no longer fits one datagram";
      socket_.sendTo(r->from, {reinterpret_cast<const std::uint8_t*>(reply.data()), reply.size()});
    }
  }
}

}  // namespace zonesim::topo
