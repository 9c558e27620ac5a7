// client_stub: N simulated players against one gateway, or logged in through the lobby to the
// gateways it names. Exits cleanly on SIGINT/SIGTERM or after --duration, writing the summary
// JSON; exits non-zero with a message on any error.

#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "clients/fd_limit.h"
#include "clients/fleet.h"
#include "clients/kind_mix.h"
#include "common/cli.h"
#include "common/log.h"
#include "common/scene.h"
#include "common/stop_signal.h"

int main(int argc, char** argv) {
  CLI::App app{"zonesim client_stub: simulated players for a gateway"};
  zonesim::CommonOptions common;
  zonesim::addCommonOptions(app, common);
  std::string scene_path, gateway_addr, metrics_dir, summary_path;
  int players = -1;
  double duration = 10;
  std::uint64_t seed = 1;
  app.add_option("--scene", scene_path, "scene file")->required();
  std::string lobby_addr;
  auto* gateway_opt =
      app.add_option("--gateway", gateway_addr,
                     "gateway address HOST:PORT (IPv4: a dotted address or a host name)");
  auto* lobby_opt =
      app.add_option("--lobby", lobby_addr,
                     "log each player in through the lobby at HOST:PORT, then say Hello "
                     "with its connect token to the gateway it was given");
  gateway_opt->excludes(lobby_opt);
  double login_timeout = zonesim::clients::LobbyLoginSettings{}.timeout_s;
  app.add_option("--login-timeout", login_timeout,
                 "with --lobby: give up if a player has no gateway after this many seconds")
      ->check(CLI::PositiveNumber);
  app.add_option("--players", players, "simulated players (default: the scene's clients.players)")
      ->check(CLI::Range(1, 100000));
  app.add_option("--duration", duration, "seconds to run")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "seed of the players' wander targets");
  app.add_option("--metrics", metrics_dir,
                 "write DIR/clients.jsonl (a line per second) and DIR/own_stream.csv");
  app.add_option("--summary", summary_path, "write the summary JSON here");
  double inject_loss = 0, inject_delay_ms = 0, inject_jitter_ms = 0;
  bool snap = false;
  auto* loss_opt =
      app.add_option("--inject-loss", inject_loss, "drop this fraction of datagrams (testing)")
          ->check(CLI::Range(0.0, 1.0));
  auto* delay_opt =
      app.add_option("--inject-delay-ms", inject_delay_ms, "delay outgoing datagrams (testing)")
          ->check(CLI::NonNegativeNumber);
  auto* jitter_opt = app.add_option("--inject-jitter-ms", inject_jitter_ms,
                                    "plus uniform jitter, which reorders (testing)")
                         ->check(CLI::NonNegativeNumber);
  std::string link, link_mix;
  auto* link_opt = app.add_option("--link", link,
                                  "every player's uplink and downlink: a preset (lan, wifi, 4g, "
                                  "congested, satellite) or a profile file (docs/networking.md)");
  auto* mix_opt = app.add_option("--link-mix", link_mix,
                                 "profiles shared out over the players, e.g. lan:0.5,4g:0.5");
  link_opt->excludes(mix_opt);
  for (auto* inject : {loss_opt, delay_opt, jitter_opt}) {
    link_opt->excludes(inject);
    mix_opt->excludes(inject);
  }
  std::uint32_t truth_every = 0;
  app.add_option("--truth-every", truth_every,
                 "with --metrics: write DIR/display.csv, where every K-th entity id was shown "
                 "each tick (zone_node --truth-every K writes the truth)");
  app.add_flag("--snap", snap, "show corrections at once instead of blending them in");
  std::string kind;
  app.add_option("--kind", kind,
                 "make every player this kind (walker, rider or flyer: one of the scene's "
                 "clients.kinds; default: the kinds mixed by their shares)");
  double max_lead_s = zonesim::clients::PlayerConfig{}.max_lead_s;
  app.add_option("--max-lead-s", max_lead_s,
                 "the server-clock estimate runs at most this far past the newest tick heard "
                 "(0: unbounded, for comparison)")
      ->check(CLI::NonNegativeNumber);
  double resume_after_s = zonesim::clients::PlayerConfig{}.resume_after_s;
  app.add_option("--resume-after-s", resume_after_s,
                 "a gateway silent this long is taken for dead: the player says Hello again with "
                 "its resume token, to it (restarted) or a --fallback-gateway (0: never)")
      ->check(CLI::NonNegativeNumber);
  std::uint32_t input_redundancy = zonesim::clients::PlayerConfig{}.input_redundancy;
  app.add_option("--input-redundancy", input_redundancy,
                 "earlier inputs each input datagram carries again, so that a lost one reaches "
                 "the zone with the next (0: none)")
      ->check(CLI::Range(0, int(zonesim::gateway::kMaxEarlierInputs)));
  double leaderboard_every_s = 0;
  app.add_option("--leaderboard-every-s", leaderboard_every_s,
                 "each player asks for the leaderboard this often (0: never)")
      ->check(CLI::NonNegativeNumber);
  double transactions_per_s = 0;
  app.add_option("--transactions-per-s", transactions_per_s,
                 "transactions (loot, purchases, scores) each player makes a second on its "
                 "reliable channel; the zones commit them to their ledger (0: none)")
      ->check(CLI::Range(0.0, 1000.0));
  std::vector<std::string> fallback_gateways;
  app.add_option("--fallback-gateway", fallback_gateways,
                 "HOST:PORT of another gateway of the cluster to resume at (repeatable)");
  CLI11_PARSE(app, argc, argv);
  // First, so a signal during start-up also ends in a clean exit rather than a kill.
  zonesim::installStopSignals();

  zonesim::clients::FleetConfig cfg;
  try {
    zonesim::applyCommonOptions(common, "clients");
    zonesim::Scene scene = zonesim::loadScene(scene_path);
    if (gateway_addr.empty() && lobby_addr.empty())
      throw std::runtime_error("--gateway or --lobby is required: where the players connect");
    try {
      if (!gateway_addr.empty())
        cfg.player.gateway = zonesim::gateway::resolveEndpoint(gateway_addr);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error("--gateway " + gateway_addr + ": " + e.what());
    }
    if (!lobby_addr.empty()) {
      zonesim::clients::LobbyLoginSettings login;
      try {
        login.lobby = zonesim::gateway::resolveEndpoint(lobby_addr);
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error("--lobby " + lobby_addr + ": " + e.what());
      }
      login.timeout_s = login_timeout;
      login.seed = seed;
      cfg.lobby = login;
    }
    cfg.player.world = scene.world;
    cfg.player.input_hz = scene.clients.input_hz;
    cfg.player.retarget_seconds = scene.clients.retarget_seconds;
    cfg.player.seed = seed;
    cfg.player.impairment =
        zonesim::gateway::injectedImpairment(inject_loss, inject_delay_ms, inject_jitter_ms);
    cfg.player.impairment.seed = seed;
    try {
      if (!link.empty()) cfg.links = {{zonesim::gateway::loadLinkProfile(link), 1.0}};
      if (!link_mix.empty()) cfg.links = zonesim::gateway::parseLinkMix(link_mix);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string(link.empty() ? "--link-mix" : "--link") + ": " +
                                  e.what());
    }
    try {
      cfg.kinds = zonesim::clients::fleetKinds(scene.clients, kind);
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error("--kind: " + std::string(e.what()));
    }
    cfg.player.blend = !snap;
    cfg.player.truth_every = truth_every;
    cfg.player.max_lead_s = max_lead_s;
    cfg.player.resume_after_s = resume_after_s;
    cfg.player.transactions_per_s = transactions_per_s;
    cfg.player.input_redundancy = input_redundancy;
    cfg.player.leaderboard_every_s = leaderboard_every_s;
    for (const std::string& g : fallback_gateways) {
      try {
        cfg.player.fallback_gateways.push_back(zonesim::gateway::resolveEndpoint(g));
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error("--fallback-gateway " + g + ": " + e.what());
      }
    }
    // Heartbeat + 2 s: with --max-lead-s 0 the player's server clock may run up to 1 s ahead of
    // the zones before it falls back (sim_player.cpp), so 1 s of margin alone counts a late
    // heartbeat as a ghost.
    cfg.player.stale_after_s = scene.dead_reckoning.heartbeat_seconds + 2.0;
    cfg.players = players > 0 ? players : scene.clients.players;
    cfg.duration_s = duration;
    if (!metrics_dir.empty()) {
      std::filesystem::create_directories(metrics_dir);
      cfg.metrics_path = metrics_dir + "/clients.jsonl";
      cfg.own_stream_path = metrics_dir + "/own_stream.csv";
      if (truth_every > 0) cfg.display_path = metrics_dir + "/display.csv";
    }
    zonesim::clients::ClientFleet fleet(cfg);
    fleet.run(zonesim::stopRequested());
    std::string summary = fleet.summaryJson();
    if (!summary_path.empty()) {
      std::ofstream f(summary_path);
      if (!f) throw std::runtime_error("cannot write " + summary_path);
      f << summary << '\n';
    }
    if (cfg.lobby)
      std::printf("clients logged in %zu of %d through lobby %s\n", fleet.tickets().size(),
                  cfg.players, cfg.lobby->lobby.str().c_str());
    const zonesim::clients::FleetCost& cost = fleet.cost();
    std::printf(
        "clients welcomed %d of %d; fleet cpu %.2f s, %.1f us per player-second, %.0f "
        "wake-ups/s\n",
        fleet.welcomed(), cfg.players, cost.cpu_s,
        zonesim::clients::cpuUsPerPlayerSecond(cost, fleet.players().size()),
        zonesim::clients::wakeupsPerSecond(cost));
    std::fflush(stdout);
  } catch (const zonesim::clients::FdLimitError& e) {
    std::fprintf(stderr,
                 "client_stub: error: --players %d needs %zu file descriptors, above the hard "
                 "limit of %llu (RLIMIT_NOFILE); raise it (ulimit -Hn) or run fewer players\n",
                 cfg.players, e.needed(), static_cast<unsigned long long>(e.hard()));
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "client_stub: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
