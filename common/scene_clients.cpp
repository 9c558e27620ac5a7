#include "common/scene_clients.h"

namespace zonesim {

std::vector<PlayerKind> playerKinds(const ClientProfile& clients) {
  if (!clients.kinds.empty()) return clients.kinds;
  return {PlayerKind{PlayerKindId::Walker, clients.speed, clients.nimbus, 0, 1}};
}

std::optional<PlayerKind> playerKind(const ClientProfile& clients, std::uint8_t id) {
  for (const PlayerKind& k : playerKinds(clients))
    if (std::uint8_t(k.id) == id) return k;
  return std::nullopt;
}

}  // namespace zonesim
