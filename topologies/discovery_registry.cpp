#include "topologies/discovery_registry.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace zonesim::topo {

void DiscoveryRegistry::add(const Registration& r, double now_s, double ttl_s) {
  if (!std::isfinite(ttl_s) || ttl_s <= 0 || ttl_s > kMaxTtlSeconds)
    throw std::invalid_argument("time to live " + std::to_string(ttl_s) + " s is not in (0, " +
                                std::to_string(int(kMaxTtlSeconds)) + "]");
  entries_[r.player] = {r, now_s + ttl_s};
}

std::vector<Registration> DiscoveryRegistry::list(double now_s) {
  std::vector<Registration> alive;
  for (auto it = entries_.begin(); it != entries_.end();) {
    if (it->second.expires_s <= now_s) {
      it = entries_.erase(it);
      continue;
    }
    alive.push_back(it->second.registration);
    ++it;
  }
  return alive;
}

}  // namespace zonesim::topo
