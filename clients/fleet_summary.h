#pragma once
// JSON forms of the players' counters: the per-second line and the final summary.

#include <memory>
#include <string>
#include <vector>

#include "clients/sim_player.h"
#include "common/metrics.h"

namespace zonesim::clients {

/// Sum of all players' counters; samples (RTT, error) are merged only when asked (costly).
PlayerCounters totalCounters(const std::vector<std::unique_ptr<SimPlayer>>& players, bool samples);
/// One clients.jsonl line: cumulative totals, rates over the last interval, gauges.
JsonLine fleetMetricsLine(const std::vector<std::unique_ptr<SimPlayer>>& players, double t,
                          const PlayerCounters& now, const PlayerCounters& before,
                          double interval_s);
/// What the fleet's own loop cost over a run.
struct FleetCost {
  double run_s = 0;  ///< the loop's wall time
  /// CPU time of the loop's thread: the fleet's own, even beside a gateway in one test process.
  double cpu_s = 0;
  double process_cpu_s = 0;   ///< every thread's, over the same span (client_stub has one)
  std::uint64_t wakeups = 0;  ///< returns from the loop's readiness wait
};
/// CPU microseconds per player per second of run: what one more player costs the fleet.
double cpuUsPerPlayerSecond(const FleetCost& cost, std::size_t players);
/// Loop wake-ups per second of run.
double wakeupsPerSecond(const FleetCost& cost);

/// {"players", "duration_s", "started_monotonic_s", "fleet_cpu_s", "fleet_process_cpu_s",
/// "fleet_cpu_us_per_player_s", "fleet_wakeups_per_s", "clients": [...], "totals": {...}}.
/// started_monotonic_s: the start (own_stream.csv's t_ms 0) on CLOCK_MONOTONIC, so that other
/// processes of the machine can place their events on the players' timeline.
std::string fleetSummaryJson(const std::vector<std::unique_ptr<SimPlayer>>& players,
                             double duration_s, const FleetCost& cost,
                             double started_monotonic_s = 0);

}  // namespace zonesim::clients
