#pragma once
// The gateway's counters and their JSON forms: one flat line per second in gateway.jsonl, and a
// summary at exit that adds per-player traffic.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/metrics.h"
#include "gateway/session_table.h"
#include "wire/wire_verify.h"

namespace zonesim::gateway {

/// Cumulative counters since start.
struct GatewayCounters {
  std::uint64_t datagrams_in = 0, bytes_in = 0;
  std::uint64_t datagrams_out = 0, bytes_out = 0, send_failures = 0;
  std::uint64_t updates_forwarded = 0, spawns_sent = 0, despawns_sent = 0;
  std::uint64_t resent = 0, acks_received = 0;
  std::uint64_t inputs_forwarded = 0, input_write_failures = 0;
  /// Transactions passed on to zones (repeats included), their failed writes, and outcomes
  /// told to this gateway's players or meant for another gateway's.
  std::uint64_t transactions_forwarded = 0, transaction_write_failures = 0;
  std::uint64_t outcomes_delivered = 0, outcomes_foreign = 0;
  /// Leaderboard queries passed on to zones, and answers passed on to players.
  std::uint64_t leaderboard_queries = 0, leaderboard_write_failures = 0;
  std::uint64_t leaderboards_delivered = 0;
  std::uint64_t spawn_requests = 0, welcomes = 0, handoffs = 0;
  std::uint64_t handoffs_resent = 0;  ///< Handoff notices sent again for want of an ack
  std::uint64_t clock_ticks = 0;      ///< empty StateBatches sent to quiet views
  std::uint64_t sessions_opened = 0, sessions_closed = 0, sessions_expired = 0;
  std::uint64_t sessions_resumed = 0;   ///< opened by a resume token: a player whose gateway died
  std::uint64_t sessions_replaced = 0;  ///< live ones a resume of the same player took over
  std::uint64_t dds_samples = 0, ownership_foreign = 0, ownership_stale = 0;
  std::uint64_t deferred = 0;  ///< spawns, updates and despawns held back a tick for want of budget
  std::uint64_t held = 0;      ///< updates not sent: the error shown stayed within the angle
  std::uint64_t epochs_entered = 0;      ///< cluster restarts followed
  std::uint64_t epoch_stale = 0;         ///< samples and events of an older epoch, dropped
  std::uint64_t inputs_resent = 0;       ///< inputs sent again to a restored zone (first burst)
  std::uint64_t inputs_recovered = 0;  ///< lost on the way here, forwarded from a later copy
  std::uint64_t inputs_unresendable = 0;  ///< ones it lacked that the history no longer held
  std::uint64_t avatars_reasked = 0;     ///< spawns asked again: the restored world lacked them
  std::uint64_t entities_retired = 0;    ///< cached entities the restored world did not bring
};

/// Wall time of gateway ticks (everything but receiving datagrams), in milliseconds.
struct TickTimes {
  std::uint64_t count = 0;
  double sum_ms = 0, max_ms = 0;
  void add(double ms) {
    ++count;
    sum_ms += ms;
    max_ms = ms > max_ms ? ms : max_ms;
  }
  double meanMs() const { return count > 0 ? sum_ms / double(count) : 0.0; }
};

/// Gauges sampled when a line is written.
struct GatewayGauges {
  double elapsed_s = 0;
  std::size_t sessions = 0, pending_sessions = 0, cells_subscribed = 0, entities_cached = 0;
  std::size_t held_spawns = 0;
  std::uint64_t zone_tick = 0;
  std::uint32_t epoch = 0;  ///< the newest cluster epoch seen
  /// Summary only: how far entities jumped when a restored world replaced them (metres).
  std::size_t epoch_jumps = 0;
  /// With --record: lean frames whose bits the bandwidth attribution could not account for.
  std::optional<std::uint64_t> record_frames_mismatched;
  double epoch_jump_m_p50 = 0, epoch_jump_m_p99 = 0, epoch_jump_m_max = 0;
  /// The zones' time dilation factor in the newest sample, and the lowest seen in the run.
  double zone_dilation = 1, zone_dilation_min = 1;
  TickTimes tick_ms;      ///< wall time of each tick (grows when the machine is oversubscribed)
  TickTimes tick_cpu_ms;  ///< the gateway thread's CPU time in each tick: its own work
  /// Whole-process CPU (every thread: receiving datagrams, DDS) per tick, ms.
  double process_cpu_ms_per_tick = 0;
  /// UDP payload bytes sent to clients as kbit/s: per line, over its second (median and most
  /// of the clients); in the summary, the median client's mean over its session, and the
  /// most any client was sent in one second of the run.
  double client_kbps_p50 = 0, client_kbps_max = 0;
};

/// Traffic of one player, kept after the session ends for the summary.
struct PlayerRecord {
  std::uint64_t player_id = 0;
  double seconds = 0;
  SessionTraffic traffic;
  PlayerKindId kind = PlayerKindId::Walker;
};

/// One per-second metrics line.
JsonLine metricsLine(const GatewayCounters& c, const DropCounters& drops, const GatewayGauges& g);
/// The exit summary as one JSON object (counters, drops by reason, sessions by player kind,
/// per-player traffic).
std::string summaryJson(const GatewayCounters& c, const DropCounters& drops, const GatewayGauges& g,
                        const std::vector<PlayerRecord>& players);

}  // namespace zonesim::gateway
