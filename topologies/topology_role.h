#pragma once
// What a topology_node process is in its topology (docs/networking.md, "Topologies"): the
// host of a client-hosted game, one of its clients, or a peer among peers.

#include <string>
#include <string_view>

namespace zonesim::topo {

/// A node's part in its topology.
enum class Role { Host, Client, Peer };

/// "host", "client" or "peer".
const char* roleName(Role role);

/// The role named by text; throws std::invalid_argument quoting the text and listing the roles.
Role parseRole(std::string_view text);

}  // namespace zonesim::topo
