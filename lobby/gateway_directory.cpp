#include "lobby/gateway_directory.h"

namespace zonesim::lobby {

GatewayDirectory::GatewayDirectory(std::int64_t stale_after_ns) : stale_after_ns_(stale_after_ns) {}

void GatewayDirectory::report(const GatewayReport& r, std::int64_t now_ns) {
  auto [it, fresh] = gateways_.try_emplace(r.gateway_id);
  GatewayEntry& e = it->second;
  // A restarted gateway counts logins from 0 again: nothing to settle from the difference.
  bool same_process = !fresh && e.last.incarnation == r.incarnation && r.logins >= e.last.logins;
  if (same_process) {
    // Logins settle the oldest grants first: players log in about in the order they asked.
    std::uint64_t settled = r.logins - e.last.logins;
    while (settled > 0 && !e.in_flight.empty()) {
      e.in_flight.pop_front();
      --settled;
    }
  }
  e.last = r;
  e.heard_ns = now_ns;
}

const GatewayEntry* GatewayDirectory::pick(std::int64_t now_ns, std::uint64_t now_unix_ms) {
  const GatewayEntry* best = nullptr;
  for (auto& [id, e] : gateways_) {
    // Expiries are in grant order (one token lifetime): the expired ones are at the front.
    while (!e.in_flight.empty() && e.in_flight.front() <= now_unix_ms) e.in_flight.pop_front();
    if (now_ns - e.heard_ns > stale_after_ns_) continue;
    if (load(e) >= e.last.max_sessions) continue;
    if (best == nullptr || load(e) < load(*best)) best = &e;
  }
  return best;
}

void GatewayDirectory::granted(std::uint16_t gateway_id, std::uint64_t expiry_unix_ms) {
  auto it = gateways_.find(gateway_id);
  if (it == gateways_.end()) return;
  it->second.in_flight.push_back(expiry_unix_ms);
  ++it->second.granted;
}

std::uint64_t GatewayDirectory::load(const GatewayEntry& e) {
  return std::uint64_t(e.last.sessions) + e.in_flight.size();
}

std::size_t GatewayDirectory::live(std::int64_t now_ns) const {
  std::size_t n = 0;
  for (const auto& [id, e] : gateways_) n += now_ns - e.heard_ns <= stale_after_ns_ ? 1 : 0;
  return n;
}

}  // namespace zonesim::lobby
