#include "lobby/lobby.h"

#include <poll.h>

#include <cerrno>
#include <system_error>

#include "auth/connect_token.h"
#include "common/metrics.h"
#include "common/timer.h"

namespace zonesim::lobby {

namespace {
constexpr int kWakeMs = 100;
// Bounded so a flood of requests cannot keep load reports from being read.
constexpr int kMaxDatagramsPerWake = 4096;
}  // namespace

Lobby::Lobby(const LobbyConfig& config, auth::AuthKey key)
    : socket_(config.bind),
      directory_(std::int64_t(config.stale_after_s * 1e9)),
      service_(std::move(key), directory_, config.login),
      listener_(config.dds_domain),
      rx_buffer_(gateway::kMaxDatagramBytes + 1) {}

void Lobby::run(const std::atomic<bool>& stop, double duration_s) {
  std::int64_t end_ns = duration_s > 0 ? nowNs() + std::int64_t(duration_s * 1e9) : INT64_MAX;
  while (!stop.load(std::memory_order_relaxed)) {
    std::int64_t now = nowNs();
    if (now >= end_ns) break;
    listener_.take(directory_, now);
    pollfd p{socket_.fd(), POLLIN, 0};
    int r = ::poll(&p, 1, kWakeMs);
    if (r < 0 && errno != EINTR) throw std::system_error(errno, std::generic_category(), "poll");
    if (r > 0) {
      // Reports first: a burst of logins right after a gateway's report sees it.
      listener_.take(directory_, nowNs());
      receiveAll(nowNs());
    }
  }
}

void Lobby::receiveAll(std::int64_t now_ns) {
  for (int i = 0; i < kMaxDatagramsPerWake; ++i) {
    auto got = socket_.receive(rx_buffer_);
    if (!got) return;
    std::size_t size = got->truncated ? gateway::kMaxDatagramBytes + 1 : got->size;
    auto reply = service_.handle(std::span(rx_buffer_.data(), std::min(size, rx_buffer_.size())),
                                 got->from, now_ns, auth::unixNowMs());
    if (reply && !socket_.sendTo(got->from, *reply)) ++send_failures_;
  }
}

std::string Lobby::summaryJson() const {
  const LoginCounters& c = service_.counters();
  JsonLine j;
  j.add("requests", c.requests)
      .add("granted", c.granted)
      .add("repeated", c.repeated)
      .add("refused_no_gateway", c.refused_no_gateway)
      .add("refused_full", c.refused_full)
      .add("refused_starting", c.refused_starting)
      .add("send_failures", send_failures_)
      .add("dropped_total", service_.drops().total());
  JsonLine drops;
  for (std::size_t r = 0; r < std::size_t(gateway::DropReason::Count); ++r)
    drops.add(gateway::dropReasonName(gateway::DropReason(r)),
              service_.drops()[gateway::DropReason(r)]);
  j.addRaw("dropped", drops.str());
  std::string list = "[";
  for (const auto& [id, e] : directory_.entries()) {
    if (list.size() > 1) list += ',';
    JsonLine g;
    g.add("gateway_id", std::uint64_t(id))
        .add("address", e.last.address.str())
        .add("granted", e.granted)
        .add("sessions", std::uint64_t(e.last.sessions))
        .add("logins", e.last.logins);
    list += g.str();
  }
  j.addRaw("gateways", list + "]");
  return j.str();
}

}  // namespace zonesim::lobby
