#pragma once
// A topology_node's settings, from its command line (topologies/topology_node_main.cpp).

#include <cstdint>
#include <string>

#include "topologies/topology_role.h"
#include "wire/impairment.h"
#include "wire/udp_socket.h"

namespace zonesim::topo {

/// What a node fakes, if anything (docs/networking.md, "Topologies": the cheating test). Vote
/// and equivocate are a peer's: it votes against every other peer (and forges votes in their
/// names), or shows its teleports to a bare majority of the others and the truth to the rest.
enum class Cheat { None, Teleport, Speed, Hit, Vote, Equivocate };

const char* cheatName(Cheat cheat);
/// Throws std::invalid_argument quoting the text and listing the cheats.
Cheat parseCheat(const std::string& text);

/// The cheats a node plays at once.
struct Cheats {
  bool teleport = false, speed = false, hit = false, vote = false, equivocate = false;
  bool has(Cheat c) const {
    switch (c) {
      case Cheat::Teleport:
        return teleport;
      case Cheat::Speed:
        return speed;
      case Cheat::Hit:
        return hit;
      case Cheat::Vote:
        return vote;
      case Cheat::Equivocate:
        return equivocate;
      case Cheat::None:
        break;
    }
    return false;
  }
  /// Only a peer can play it.
  bool peerOnly() const { return vote || equivocate; }
  /// "none" or the names joined by commas.
  std::string names() const;
};
/// A comma-separated list ("teleport,hit", "none"); throws as parseCheat on any name.
Cheats parseCheats(const std::string& text);

struct NodeConfig {
  Role role = Role::Peer;
  std::uint32_t player = 0;
  std::uint32_t players = 16;  ///< in the game, the host included
  std::string scene_path;
  gateway::Endpoint discovery;
  gateway::Endpoint bind;     ///< this node's UDP address (port 0: ephemeral)
  std::uint64_t token = 0;    ///< the game's key: frames' checksums, inputs' token
  std::int64_t start_ns = 0;  ///< CLOCK_REALTIME of tick 0, shared by every node
  double duration_s = 10;
  double join_timeout_s = 20;  ///< waiting for the others through discovery
  std::string out_dir;
  Cheats cheats;
  double cheat_seconds = 0;  ///< cheat for this long from tick 0, then play honestly (0: always)
  bool cross_check = false;  ///< a client checks the host's states and hits
  std::uint64_t seed = 0;    ///< 0: the scene's
  /// This player's access link, the same profile both ways as client_stub --link gives its
  /// players (off by default): a datagram between two players crosses two such links.
  gateway::ImpairmentSettings link;
};

}  // namespace zonesim::topo
