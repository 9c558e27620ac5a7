#pragma once
// What a zone writes about its run: one JSON line per tick (phases and counters) while running,
// and one summary object at the end (entities, migrations, handoffs, tick-time percentiles).

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "common/metrics.h"
#include "common/timer.h"
#include "zone_node/zone_node.h"

namespace zonesim::zone {

/// Accumulates a zone's run figures tick by tick.
class ZoneReport {
 public:
  explicit ZoneReport(const ZoneNode& zone);

  /// Records the tick just run (and writes its JSON line when metrics are on).
  void recordTick(const ZoneNode& zone, double tick_seconds, MetricsWriter& metrics);
  /// Records the wall period of the tick just run when paced in real time, and whether its
  /// work ended after its deadline (call before recordTick, which writes it).
  void recordPacing(const ZoneNode& zone, double period_seconds, bool late);
  /// The end-of-run summary as one JSON object.
  std::string summaryJson(const ZoneNode& zone, double wall_seconds) const;

 private:
  std::uint64_t entities_start_;
  std::uint64_t id_hash_start_ = 0;  // IdSetDigest hash of the ids the run began with
  std::vector<double> tick_ms_;
  TickProfile phase_totals_;
  TickCounters totals_;  // event counters summed; gauges hold their last value
  std::vector<double> handoff_latency_ms_;
  // Per destination rank, so a run across hosts can show which moves crossed a host boundary.
  std::map<int, std::uint64_t> migrated_to_;
  std::map<int, std::uint64_t> avatars_to_;
  double min_factor_ = 1;  // the slowest clock rate run at
  std::uint64_t dilated_ticks_ = 0;
  double dilated_wall_s_ = 0;     // paced wall seconds of the dilated ticks
  std::uint64_t late_ticks_ = 0;  // paced ticks whose work overran their deadline
  double factor_ = 1;             // of the tick last recorded
  bool late_ = false;             // the tick being recorded ended after its deadline
  Stopwatch since_start_;         // wall time of each metrics line, for per-second figures
};

}  // namespace zonesim::zone
