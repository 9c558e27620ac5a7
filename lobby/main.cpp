// lobby: where players log in. Hands each one a connect token, signed with the cluster's key,
// for the least-loaded gateway that reports on DDS. Prints "lobby listening on ADDR:PORT" once
// ready; exits cleanly on SIGINT/SIGTERM or after --duration, printing a JSON summary line;
// exits non-zero with a message on any error.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>
#include <stdexcept>

#include "auth/auth_key.h"
#include "common/cli.h"
#include "common/log.h"
#include "common/stop_signal.h"
#include "common/text_file.h"
#include "lobby/lobby.h"

int main(int argc, char** argv) {
  CLI::App app{"zonesim lobby: hands players signed connect tokens for the least-loaded gateway"};
  zonesim::CommonOptions common;
  zonesim::addCommonOptions(app, common);
  zonesim::lobby::LobbyConfig cfg;
  zonesim::ListenOptions listen_opts;
  std::string metrics_dir, key_file;
  double duration = 0, lifetime_s = 30;
  zonesim::addListenOptions(app, listen_opts, "players' logins");
  app.add_option("--auth-key-file", key_file,
                 "the cluster's key, shared with the gateways (at least 32 random bytes: "
                 "head -c 32 /dev/urandom > FILE)")
      ->required();
  app.add_option("--dds-domain", cfg.dds_domain, "DDS domain id of the gateways' load reports")
      ->check(CLI::Range(0, 232));
  app.add_option("--token-lifetime", lifetime_s,
                 "seconds a connect token opens a session after it is granted")
      ->check(CLI::Range(1.0, 3600.0));
  app.add_option("--gateway-stale", cfg.stale_after_s,
                 "seconds without a load report after which a gateway gets no more players")
      ->check(CLI::PositiveNumber);
  app.add_option("--expect-gateways", cfg.login.expect_gateways,
                 "hold logins (refused, to retry) until this many gateways have reported "
                 "(default 1)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--metrics", metrics_dir, "write DIR/lobby_summary.json at exit");
  app.add_option("--duration", duration, "exit after this many seconds (0 = until signalled)")
      ->check(CLI::NonNegativeNumber);
  CLI11_PARSE(app, argc, argv);
  zonesim::installStopSignals();

  try {
    zonesim::applyCommonOptions(common, "lobby");
    std::string bind_option = zonesim::gateway::bindOptionText(listen_opts.bind, listen_opts.port);
    cfg.bind = zonesim::gateway::bindFromOptions(listen_opts.bind, listen_opts.port);
    zonesim::auth::AuthKey key = zonesim::auth::loadAuthKey(key_file);
    cfg.login.token_lifetime_ms = std::uint64_t(lifetime_s * 1000);
    // Player ids of a restarted lobby differ from the ones it issued before.
    // 15 bits, as a gateway's: player ids stay below 2^63 for the ledger (gateway/gateway.cpp).
    cfg.login.incarnation = std::uint16_t(1 + std::random_device{}() % 0x7FFF);
    std::optional<zonesim::lobby::Lobby> bound;
    try {
      bound.emplace(cfg, std::move(key));
    } catch (const zonesim::gateway::BindError& e) {
      throw std::runtime_error(bind_option + ": " + e.what());
    }
    zonesim::lobby::Lobby& lobby = *bound;
    if (!listen_opts.port_file.empty())
      zonesim::writeTextFileAtomically(listen_opts.port_file, std::to_string(lobby.local().port));
    std::printf("lobby listening on %s\n", lobby.local().str().c_str());
    std::fflush(stdout);
    lobby.run(zonesim::stopRequested(), duration);
    std::string summary = lobby.summaryJson();
    std::printf("lobby summary %s\n", summary.c_str());
    std::fflush(stdout);
    if (!metrics_dir.empty()) {
      std::filesystem::create_directories(metrics_dir);
      zonesim::writeTextFileAtomically(metrics_dir + "/lobby_summary.json", summary);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lobby: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
