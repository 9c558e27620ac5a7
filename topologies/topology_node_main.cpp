// topology_node: one player of a client-hosted or peer-to-peer game (docs/networking.md,
// "Topologies"); bench/net/topology_bench.py starts one per player.
#include <cstdio>
#include <filesystem>

#include "common/cli.h"
#include "common/scene.h"
#include "common/stop_signal.h"
#include "topologies/discovery_message.h"
#include "topologies/topology_node.h"
#include "wire/link_profile.h"

int main(int argc, char** argv) {
  CLI::App app{"zonesim topology_node: one player of a client-hosted or peer-to-peer game"};
  zonesim::CommonOptions common;
  zonesim::addCommonOptions(app, common);
  zonesim::topo::NodeConfig cfg;
  std::string role, discovery, bind = "127.0.0.1", token, cheat = "none";
  double start_at = 0;
  app.add_option("--role", role, "host, client or peer")->required();
  app.add_option("--player", cfg.player, "this player's number, 0..players-1")->required();
  app.add_option("--players", cfg.players, "players in the game, the host included")
      ->check(CLI::Range(1u, 64u));
  app.add_option("--scene", cfg.scene_path, "scene file (arena, tick, avatar speed)")->required();
  app.add_option("--discovery", discovery, "the discovery service, A.B.C.D:PORT")->required();
  app.add_option("--bind", bind, "this node's IPv4 address, as registered (default 127.0.0.1)");
  app.add_option("--token", token, "the game's key, 16 hex digits, shared by every node")
      ->required();
  app.add_option("--start-at", start_at, "wall-clock time of tick 0, seconds since the epoch")
      ->required();
  app.add_option("--duration", cfg.duration_s, "seconds to play")->check(CLI::PositiveNumber);
  app.add_option("--join-timeout", cfg.join_timeout_s, "seconds to wait for the others")
      ->check(CLI::PositiveNumber);
  app.add_option("--out", cfg.out_dir, "write views, events and the summary here")->required();
  app.add_option("--cheat", cheat,
                 "none, or teleport, speed, hit (and a peer's vote, equivocate) joined by commas");
  app.add_option("--cheat-seconds", cfg.cheat_seconds,
                 "cheat for this many seconds of play, then play honestly (default: all along)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--cross-check", cfg.cross_check,
               "a client holds the host's states and hits to the movement limits");
  app.add_option("--seed", cfg.seed, "seed of the scripted inputs (default: the scene's)");
  std::string link;
  app.add_option("--link", link,
                 "this player's uplink and downlink: a preset (lan, wifi, 4g, congested, "
                 "satellite) or a profile file, as client_stub --link");
  CLI11_PARSE(app, argc, argv);
  zonesim::installStopSignals();
  try {
    zonesim::applyCommonOptions(common, "topology_node");
    try {
      cfg.role = zonesim::topo::parseRole(role);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--role: ") + e.what());
    }
    try {
      cfg.cheats = zonesim::topo::parseCheats(cheat);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--cheat: ") + e.what());
    }
    try {
      cfg.discovery = zonesim::topo::parseDottedEndpoint(discovery);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--discovery: ") + e.what());
    }
    try {
      cfg.bind = zonesim::topo::parseDottedEndpoint(bind + ":1");
      cfg.bind.port = 0;
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("--bind " + bind + ": not a dotted IPv4 address");
    }
    if (cfg.bind.address == 0)
      throw std::invalid_argument("--bind 0.0.0.0 cannot be registered: give this host's address");
    std::size_t used = 0;
    if (token.size() != 16 || (cfg.token = std::stoull(token, &used, 16), used != 16) ||
        cfg.token == 0)
      throw std::invalid_argument("--token '" + token +
                                  "' is not 16 hex digits (and not all zero)");
    cfg.start_ns = std::int64_t(start_at * 1e9);
    if (!link.empty()) {
      try {
        cfg.link.out = cfg.link.in = zonesim::gateway::loadLinkProfile(link);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("--link: ") + e.what());
      }
      cfg.link.seed = cfg.seed ? cfg.seed : 1;
    }
    std::filesystem::create_directories(cfg.out_dir);
    zonesim::Scene scene = zonesim::loadScene(cfg.scene_path);
    zonesim::topo::TopologyNode node(cfg, scene);
    node.run();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "topology_node: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
