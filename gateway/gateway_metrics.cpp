#include "gateway/gateway_metrics.h"

#include <array>
#include <string>

namespace zonesim::gateway {

namespace {

void addCounters(JsonLine& j, const GatewayCounters& c) {
  j.add("datagrams_in", c.datagrams_in)
      .add("bytes_in", c.bytes_in)
      .add("datagrams_out", c.datagrams_out)
      .add("bytes_out", c.bytes_out)
      .add("send_failures", c.send_failures)
      .add("updates_forwarded", c.updates_forwarded)
      .add("resent", c.resent)
      .add("spawns_sent", c.spawns_sent)
      .add("despawns_sent", c.despawns_sent)
      .add("inputs_forwarded", c.inputs_forwarded)
      .add("input_write_failures", c.input_write_failures)
      .add("transactions_forwarded", c.transactions_forwarded)
      .add("transaction_write_failures", c.transaction_write_failures)
      .add("outcomes_delivered", c.outcomes_delivered)
      .add("outcomes_foreign", c.outcomes_foreign)
      .add("leaderboard_queries", c.leaderboard_queries)
      .add("leaderboard_write_failures", c.leaderboard_write_failures)
      .add("leaderboards_delivered", c.leaderboards_delivered)
      .add("spawn_requests", c.spawn_requests)
      .add("welcomes", c.welcomes)
      .add("handoffs", c.handoffs)
      .add("handoffs_resent", c.handoffs_resent)
      .add("clock_ticks", c.clock_ticks)
      .add("sessions_opened", c.sessions_opened)
      .add("sessions_closed", c.sessions_closed)
      .add("sessions_expired", c.sessions_expired)
      .add("sessions_resumed", c.sessions_resumed)
      .add("sessions_replaced", c.sessions_replaced)
      .add("dds_samples", c.dds_samples)
      .add("ownership_foreign", c.ownership_foreign)
      .add("ownership_stale", c.ownership_stale)
      .add("deferred", c.deferred)
      .add("held", c.held)
      .add("epochs_entered", c.epochs_entered)
      .add("epoch_stale", c.epoch_stale)
      .add("inputs_resent", c.inputs_resent)
      .add("inputs_recovered", c.inputs_recovered)
      .add("inputs_unresendable", c.inputs_unresendable)
      .add("avatars_reasked", c.avatars_reasked)
      .add("entities_retired", c.entities_retired);
}

void addGauges(JsonLine& j, const GatewayGauges& g) {
  j.add("t", g.elapsed_s)
      .add("sessions", std::uint64_t(g.sessions))
      .add("pending_sessions", std::uint64_t(g.pending_sessions))
      .add("cells_subscribed", std::uint64_t(g.cells_subscribed))
      .add("entities_cached", std::uint64_t(g.entities_cached))
      .add("held_spawns", std::uint64_t(g.held_spawns))
      .add("zone_tick", g.zone_tick)
      .add("epoch", std::uint64_t(g.epoch))
      .add("zone_dilation", g.zone_dilation)
      .add("zone_dilation_min", g.zone_dilation_min)
      .add("ticks", g.tick_ms.count)
      .add("tick_ms_mean", g.tick_ms.meanMs())
      .add("tick_ms_max", g.tick_ms.max_ms)
      .add("tick_cpu_ms_mean", g.tick_cpu_ms.meanMs())
      .add("tick_cpu_ms_max", g.tick_cpu_ms.max_ms)
      .add("process_cpu_ms_per_tick", g.process_cpu_ms_per_tick)
      .add("client_kbps_p50", g.client_kbps_p50)
      .add("client_kbps_max", g.client_kbps_max);
  if (g.record_frames_mismatched) j.add("record_frames_mismatched", *g.record_frames_mismatched);
  if (g.epoch_jumps > 0)
    j.add("epoch_jumps", std::uint64_t(g.epoch_jumps))
        .add("epoch_jump_m_p50", g.epoch_jump_m_p50)
        .add("epoch_jump_m_p99", g.epoch_jump_m_p99)
        .add("epoch_jump_m_max", g.epoch_jump_m_max);
}

JsonLine dropsObject(const DropCounters& drops) {
  JsonLine j;
  for (std::size_t r = 0; r < std::size_t(DropReason::Count); ++r)
    j.add(dropReasonName(DropReason(r)), drops[DropReason(r)]);
  return j;
}

// Sessions of the run per player kind, every kind named (0 for one the scene lacks), so a
// reader never has to ask which keys exist.
JsonLine sessionsByKind(const std::vector<PlayerRecord>& players) {
  std::array<std::uint64_t, kPlayerKindCount> n{};
  for (const PlayerRecord& p : players) ++n[std::size_t(p.kind)];
  JsonLine j;
  for (std::size_t k = 0; k < kPlayerKindCount; ++k) j.add(kPlayerKindNames[k], n[k]);
  return j;
}

std::string playerJson(const PlayerRecord& p) {
  const SessionTraffic& t = p.traffic;
  double s = p.seconds > 0 ? p.seconds : 1;
  JsonLine j;
  j.add("player_id", p.player_id)
      .add("kind", playerKindName(p.kind))
      .add("seconds", p.seconds)
      .add("datagrams_in", t.datagrams_in)
      .add("bytes_in", t.bytes_in)
      .add("datagrams_out", t.datagrams_out)
      .add("bytes_out", t.bytes_out)
      .add("bytes_out_per_s", double(t.bytes_out) / s)
      .add("updates_sent", t.updates_sent)
      .add("resent", t.resent)
      .add("spawns_sent", t.spawns_sent)
      .add("despawns_sent", t.despawns_sent)
      .add("inputs_forwarded", t.inputs_forwarded)
      .add("handoffs", t.handoffs)
      .add("handoffs_resent", t.handoffs_resent)
      .add("deferred", t.deferred)
      .add("held", t.held);
  return j.str();
}

}  // namespace

JsonLine metricsLine(const GatewayCounters& c, const DropCounters& drops, const GatewayGauges& g) {
  JsonLine j;
  addGauges(j, g);
  addCounters(j, c);
  // Flat keys, so tools can plot any reason without parsing nested objects.
  for (std::size_t r = 0; r < std::size_t(DropReason::Count); ++r)
    j.add(std::string("dropped_") + dropReasonName(DropReason(r)), drops[DropReason(r)]);
  j.add("dropped_total", drops.total());
  return j;
}

std::string summaryJson(const GatewayCounters& c, const DropCounters& drops, const GatewayGauges& g,
                        const std::vector<PlayerRecord>& players) {
  JsonLine j;
  addGauges(j, g);
  addCounters(j, c);
  j.add("dropped_total", drops.total());
  j.addRaw("dropped", dropsObject(drops).str());
  j.addRaw("sessions_by_kind", sessionsByKind(players).str());
  std::string list = "[";
  for (std::size_t i = 0; i < players.size(); ++i) {
    if (i > 0) list += ',';
    list += playerJson(players[i]);
  }
  list += ']';
  j.addRaw("players", list);
  return j.str();
}

}  // namespace zonesim::gateway
