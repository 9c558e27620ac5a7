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
/// {"players", "duration_s", "clients": [...], "totals": {...}}.
std::string fleetSummaryJson(const std::vector<std::unique_ptr<SimPlayer>>& players,
                             double duration_s);

}  // namespace zonesim::clients
