#include "topologies/topology_role.h"

#include <stdexcept>

namespace zonesim::topo {

const char* roleName(Role role) {
  switch (role) {
    case Role::Host:
      return "host";
    case Role::Client:
      return "client";
    case Role::Peer:
      return "peer";
  }
  return "?";
}

Role parseRole(std::string_view text) {
  for (Role r : {Role::Host, Role::Client, Role::Peer})
    if (text == roleName(r)) return r;
  throw std::invalid_argument("role '" + std::string(text) + "' is not one of host, client, peer");
}

}  // namespace zonesim::topo
