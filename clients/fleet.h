#pragma once
// N simulated players in one process, driven by one single-threaded loop: epoll over the
// players' sockets, each ready one drained in recvmmsg batches, and a queue of each player's
// next due time, so a wake-up costs the players that have something to read or to send, not
// all N. Writes one metrics line per second and, at the end, a JSON summary per player and in
// total, with the fleet's own CPU time per player.

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "clients/fleet_summary.h"
#include "clients/lobby_login.h"
#include "clients/sim_player.h"
#include "common/metrics.h"
#include "common/stop_signal.h"
#include "wire/link_profile.h"

namespace zonesim::clients {

/// How the fleet runs.
struct FleetConfig {
  PlayerConfig player;
  /// Link profiles shared out over the players (each gets one for its uplink and downlink, by
  /// linkShareOf); empty: every player has player.impairment.
  std::vector<gateway::LinkShare> links;
  /// Player kinds shared out over the players by their shares (clients/kind_mix.h); empty:
  /// every player is player.kind.
  std::vector<PlayerKind> kinds;
  int players = 32;
  double duration_s = 10;
  std::string metrics_path;     ///< clients.jsonl; empty = none
  std::string own_stream_path;  ///< own_stream.csv: own states and handoffs; empty = none
  std::string display_path;     ///< display.csv: sampled entities as shown; empty = none
  /// Log in through this lobby first: each player then says Hello, with its connect token, to
  /// the gateway the lobby gave it (player.gateway is unused). nullopt: player.gateway, no token.
  std::optional<LobbyLoginSettings> lobby;
};

class ClientFleet {
 public:
  /// Raises the open-file limit for config.players sockets (FdLimitError past the hard limit,
  /// before any is opened), opens one socket per player and, with config.lobby, logs each in
  /// (if stop is set first, no player plays); throws on failure.
  explicit ClientFleet(const FleetConfig& config,
                       const std::atomic<bool>& stop = zonesim::stopRequested());

  /// Runs until duration_s passes or stop is set, then says Bye for every player.
  void run(const std::atomic<bool>& stop);
  /// The summary JSON (players, duration_s, clients[], totals).
  std::string summaryJson() const;
  const std::vector<std::unique_ptr<SimPlayer>>& players() const { return players_; }
  /// Where the lobby sent each player, in player order (empty without a lobby).
  const std::vector<LoginTicket>& tickets() const { return tickets_; }
  /// What logging in through the lobby counted.
  const LoginStats& loginStats() const { return login_stats_; }
  /// Players that completed the handshake.
  int welcomed() const;
  /// What the run's loop cost: its CPU time and wake-ups (zero before run()).
  const FleetCost& cost() const { return cost_; }

 private:
  void writeMetrics(std::int64_t now_ns);
  /// Sends the Byes the impaired uplinks still hold, each when due.
  void flushByes();
  /// Writes every player's own stream as CSV (player, event, t_ms, tick, server_tick).
  void writeOwnStream() const;
  /// Writes what every player showed of the sampled entities (player, tick, id, order, x, y, z).
  void writeDisplayed() const;

  FleetConfig config_;
  std::int64_t start_ns_;
  double elapsed_s_ = 0;
  FleetCost cost_;
  std::vector<std::unique_ptr<SimPlayer>> players_;
  std::vector<LoginTicket> tickets_;
  LoginStats login_stats_;
  MetricsWriter metrics_;
  PlayerCounters last_totals_;
};

}  // namespace zonesim::clients
