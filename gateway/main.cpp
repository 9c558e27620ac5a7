// gateway: UDP server for simulated players, DDS client of the zones. Prints
// "gateway listening on ADDR:PORT" once ready (the bound address: --bind, 127.0.0.1 by default);
// exits cleanly on SIGINT/SIGTERM or after
// --duration, printing a JSON summary line; exits non-zero with a message on any error.

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "auth/auth_key.h"
#include "common/cli.h"
#include "common/log.h"
#include "common/scene.h"
#include "common/stop_signal.h"
#include "common/text_file.h"
#include "gateway/gateway.h"

int main(int argc, char** argv) {
  CLI::App app{"zonesim gateway: connects simulated players to the zone cluster"};
  zonesim::CommonOptions common;
  zonesim::addCommonOptions(app, common);
  std::string scene_path, metrics_dir;
  zonesim::gateway::GatewayConfig cfg;
  double duration = 0;
  std::int64_t seed = -1;
  zonesim::ListenOptions listen_opts;
  app.add_option("--scene", scene_path, "scene file")->required();
  zonesim::addListenOptions(app, listen_opts, "players");
  app.add_option("--dds-domain", cfg.dds_domain,
                 "DDS domain id (Cyclone's default ports allow 0-232)")
      ->check(CLI::Range(0, 232));
  app.add_option("--gateway-id", cfg.gateway_id,
                 "gateway id, unique per gateway of a cluster (bits 32-47 of player ids)")
      ->check(CLI::Range(1u, 0xffffu));
  app.add_option("--metrics", metrics_dir, "write DIR/gateway.jsonl and DIR/gateway_summary.json");
  app.add_option("--record", cfg.record_dir,
                 "write a recording of every tick into this folder (gateway_<id>.zsrec: "
                 "subscribed cells, each player's visible set and bytes by field) for "
                 "deploy/inspect.sh");
  app.add_option("--record-every-ticks", cfg.record_every_ticks,
                 "with --record: a frame every this many ticks (the players' views then, their "
                 "bytes since the frame before)");
  app.add_option("--duration", duration, "exit after this many seconds (0 = until signalled)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--seed", seed, "seed of avatar spawn positions (default: the scene seed)");
  app.add_option("--expect-zones", cfg.expected_zones,
                 "zone readers to wait for before spawning (default: the scene's zone grid)");
  app.add_option("--session-timeout", cfg.session_timeout_s, "close sessions silent this long (s)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-sessions", cfg.max_sessions, "refuse Hellos beyond this many sessions");
  app.add_flag("!--no-resend", cfg.resend,
               "never resend unacknowledged updates, spawns, despawns (for comparison)");
  bool resend_early = false;
  app.add_flag("--resend-early", resend_early,
               "resend as soon as a datagram of a later tick is acknowledged, not only after "
               "the retransmission timeout (for comparison: more resends, no less error)");
  double inject_loss = 0, inject_delay_ms = 0, inject_jitter_ms = 0;
  std::string link;
  auto* link_opt = app.add_option("--link", link,
                                  "impair every client's downlink: a preset (lan, wifi, 4g, "
                                  "congested, satellite) or a profile file (docs/networking.md)");
  link_opt->excludes(
      app.add_option("--inject-loss", inject_loss, "drop this fraction of datagrams (testing)")
          ->check(CLI::Range(0.0, 1.0)));
  link_opt->excludes(
      app.add_option("--inject-delay-ms", inject_delay_ms, "delay outgoing datagrams (testing)")
          ->check(CLI::NonNegativeNumber));
  link_opt->excludes(app.add_option("--inject-jitter-ms", inject_jitter_ms,
                                    "plus uniform jitter, which reorders (testing)")
                         ->check(CLI::NonNegativeNumber));
  std::optional<double> budget_kbps, budget_angle_deg;
  app.add_option("--budget-kbps", budget_kbps,
                 "downlink budget per client, kbit/s of UDP payload (default: the scene's "
                 "clients.downlink_kbps; 0 = none)");
  app.add_option("--budget-error-angle-deg", budget_angle_deg,
                 "under a budget, hold the error each player sees as this angle (default: the "
                 "scene's clients.downlink_error_angle_deg)");
  app.add_option("--budget-send-bytes", cfg.budget.send_bytes,
                 "under a budget, gather each player's spawns and updates to about this many "
                 "bytes before they go (default 150: 2 ticks at 20 kbit/s; smaller sends show "
                 "states sooner and pay more framing)");
  app.add_option("--full-scan-every", cfg.full_scan_every_ticks,
                 "without a budget, scan each player's visibility every N ticks (staggered); "
                 "the ticks between send only what changed of what it holds (default 4; 1 = "
                 "every tick)")
      ->check(CLI::PositiveNumber);
  std::string auth_key_file, public_address, resume_key_file;
  app.add_option("--auth-key-file", auth_key_file,
                 "the cluster's key (at least 32 random bytes, shared with the lobby): every "
                 "Hello then needs the lobby's connect token, and the load goes to the lobby");
  app.add_option("--resume-key-file", resume_key_file,
                 "the key (at least 32 random bytes) the cluster's gateways share for resume "
                 "tokens: each Welcome carries one, and a player whose gateway died says Hello "
                 "with it to any of them and gets its avatar back (default: --auth-key-file; "
                 "neither: no resume)");
  app.add_option("--public-address", public_address,
                 "ADDR[:PORT] players reach this gateway at, told to the lobby (default: the "
                 "bound address and port; needed with --bind 0.0.0.0)");
  CLI11_PARSE(app, argc, argv);
  // First, so a signal during start-up also ends in a clean exit rather than a kill.
  zonesim::installStopSignals();

  try {
    zonesim::applyCommonOptions(common, "gateway");
    cfg.scene = zonesim::loadScene(scene_path);
    // What the user typed, so an error names the options at fault.
    std::string bind_option = zonesim::gateway::bindOptionText(listen_opts.bind, listen_opts.port);
    cfg.bind = zonesim::gateway::bindFromOptions(listen_opts.bind, listen_opts.port);
    cfg.impairment =
        zonesim::gateway::injectedImpairment(inject_loss, inject_delay_ms, inject_jitter_ms);
    if (!link.empty()) {
      try {
        cfg.impairment.out = zonesim::gateway::loadLinkProfile(link);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("--link: ") + e.what());
      }
    }
    // The scene's budget, unless the command line gives one; a bad one names its option.
    bool budget_from_cli = budget_kbps.has_value(), angle_from_cli = budget_angle_deg.has_value();
    cfg.budget.kbps = budget_kbps.value_or(cfg.scene.clients.downlink_kbps);
    double angle_deg = budget_angle_deg.value_or(cfg.scene.clients.downlink_error_angle_deg);
    cfg.budget.error_angle_rad = angle_deg * M_PI / 180.0;
    cfg.budget_names = {
        budget_from_cli ? "--budget-kbps" : "clients.downlink_kbps",
        angle_from_cli ? "--budget-error-angle-deg" : "clients.downlink_error_angle_deg"};
    if (!auth_key_file.empty()) cfg.auth_key = zonesim::auth::loadAuthKey(auth_key_file);
    if (!resume_key_file.empty())
      cfg.resume_key = zonesim::auth::loadAuthKey(resume_key_file);
    else
      cfg.resume_key = cfg.auth_key;
    if (!public_address.empty()) {
      if (auth_key_file.empty())
        throw std::runtime_error("--public-address is told to the lobby: it needs --auth-key-file");
      try {
        cfg.public_address = zonesim::gateway::parseBindAddress(public_address, 0);
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error("--public-address " + public_address + ": " + e.what());
      }
    }
    if (resend_early) cfg.loss_detection = zonesim::gateway::LossDetection::LaterAck;
    cfg.spawn_seed = seed >= 0 ? std::uint64_t(seed) : cfg.scene.seed;
    if (!metrics_dir.empty()) {
      std::filesystem::create_directories(metrics_dir);
      cfg.metrics_path = metrics_dir + "/gateway.jsonl";
    }
    if (!cfg.record_dir.empty()) std::filesystem::create_directories(cfg.record_dir);
    std::optional<zonesim::gateway::Gateway> bound;
    try {
      bound.emplace(cfg);
    } catch (const zonesim::gateway::BindError& e) {
      throw std::runtime_error(bind_option + ": " + e.what());
    }
    zonesim::gateway::Gateway& gateway = *bound;
    if (!listen_opts.port_file.empty())
      zonesim::writeTextFileAtomically(listen_opts.port_file, std::to_string(gateway.port()));
    std::printf("gateway listening on %s\n", gateway.local().str().c_str());
    std::fflush(stdout);
    gateway.run(zonesim::stopRequested(), duration);
    std::string summary = gateway.summaryJson();
    std::printf("gateway summary %s\n", summary.c_str());
    std::fflush(stdout);
    if (!metrics_dir.empty())
      zonesim::writeTextFileAtomically(metrics_dir + "/gateway_summary.json", summary);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gateway: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
