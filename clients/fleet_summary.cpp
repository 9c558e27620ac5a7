#include "clients/fleet_summary.h"

#include <algorithm>

#include "clients/kind_summary.h"
#include "common/stats.h"
#include "common/timer.h"

namespace zonesim::clients {

namespace {

void addSum(PlayerCounters& t, const PlayerCounters& c, bool samples) {
  t.datagrams_in += c.datagrams_in;
  t.bytes_in += c.bytes_in;
  t.datagrams_out += c.datagrams_out;
  t.bytes_out += c.bytes_out;
  t.updates += c.updates;
  t.spawns += c.spawns;
  t.despawns += c.despawns;
  t.handoffs += c.handoffs;
  t.pongs += c.pongs;
  t.hellos += c.hellos;
  t.inputs += c.inputs;
  t.send_failures += c.send_failures;
  t.duplicates += c.duplicates;
  t.stale_lifecycle += c.stale_lifecycle;
  t.repeats += c.repeats;
  t.resumes += c.resumes;
  t.resume_failed += c.resume_failed;
  t.resume_new_avatar += c.resume_new_avatar;
  t.inputs_resent += c.inputs_resent;
  t.inputs_unresendable += c.inputs_unresendable;
  t.leaderboard_queries += c.leaderboard_queries;
  t.leaderboards += c.leaderboards;
  t.leaderboards_unordered += c.leaderboards_unordered;
  t.min_dilation = std::min(t.min_dilation, c.min_dilation);
  for (std::size_t r = 0; r < std::size_t(gateway::DropReason::Count); ++r)
    t.drops.add(gateway::DropReason(r), c.drops[gateway::DropReason(r)]);
  if (!samples) return;
  t.rtt_ms.merge(c.rtt_ms);
  t.dr_error_m.merge(c.dr_error_m);
  t.resume_s.merge(c.resume_s);
}

double rate(std::uint64_t n, double s) {
  return s > 0 ? double(n) / s : 0.0;
}

// Fields common to one client and the totals.
void addTraffic(JsonLine& j, const PlayerCounters& c, double s) {
  j.add("bytes_in_per_s", rate(c.bytes_in, s))
      .add("bytes_out_per_s", rate(c.bytes_out, s))
      .add("datagrams_in_per_s", rate(c.datagrams_in, s))
      .add("datagrams_out_per_s", rate(c.datagrams_out, s))
      .add("updates_per_s", rate(c.updates, s))
      .add("bytes_in", c.bytes_in)
      .add("bytes_out", c.bytes_out)
      .add("updates", c.updates)
      .add("spawns", c.spawns)
      .add("despawns", c.despawns)
      .add("handoffs", c.handoffs)
      .add("inputs", c.inputs)
      .add("dropped", c.drops.total())
      .add("duplicates", c.duplicates)
      .add("stale_lifecycle", c.stale_lifecycle)
      .add("repeats", c.repeats)
      .add("rtt_ms_p50", percentile(c.rtt_ms.samples(), 50))
      .add("rtt_ms_p99", percentile(c.rtt_ms.samples(), 99))
      .add("dr_error_m_p50", percentile(c.dr_error_m.samples(), 50))
      .add("dr_error_m_p99", percentile(c.dr_error_m.samples(), 99))
      .add("dr_error_m_max", c.dr_error_m.max())
      .add("dilation_min", c.min_dilation)
      .add("resumes", c.resumes)
      .add("resume_failed", c.resume_failed)
      .add("resume_new_avatar", c.resume_new_avatar)
      .add("resume_inputs_resent", c.inputs_resent)
      .add("resume_inputs_unresendable", c.inputs_unresendable)
      .add("resume_s_p50", percentile(c.resume_s.samples(), 50))
      .add("resume_s_max", c.resume_s.max())
      .add("leaderboard_queries", c.leaderboard_queries)
      .add("leaderboards", c.leaderboards)
      .add("leaderboards_unordered", c.leaderboards_unordered)
      .add("leaderboard_rows", c.leaderboard_rows)
      .add("leaderboard_top", c.leaderboard_top);
}

// The player's link profile and what its models did to the datagrams each way.
void addLink(JsonLine& j, const gateway::Impairment& imp) {
  if (!imp.active()) return;
  gateway::ImpairmentCounters c = imp.counters();
  j.add("link", imp.settings().out.name)
      .add("link_out_lost", c.out.lost)
      .add("link_out_tail_dropped", c.out.tail_dropped)
      .add("link_in_lost", c.in.lost)
      .add("link_in_tail_dropped", c.in.tail_dropped)
      .add("link_corrupted", c.out.corrupted + c.in.corrupted)
      .add("link_duplicated", c.out.duplicated + c.in.duplicated)
      .add("link_reordered", c.out.reordered + c.in.reordered);
}

std::string clientJson(const SimPlayer& p, double s) {
  JsonLine j;
  j.add("player_id", p.playerId())
      .add("kind", playerKindName(p.kind()))
      .add("avatar_id", p.avatarId())
      .add("zone", p.zone())
      .add("welcomed", p.welcomed() ? 1 : 0)
      .add("welcome_ms", p.welcomed() ? p.welcomeSeconds() * 1e3 : -1.0);
  addTraffic(j, p.counters(), s);
  const TransactionCounters& t = p.transactionCounters();
  j.add("transactions_made", t.made)
      .add("transactions_committed", t.committed)
      .add("transactions_failed", t.failed + t.conflicts)
      .add("transactions_pending", std::uint64_t(p.pendingTransactions()));
  std::int64_t now = nowNs();
  j.add("visible_entities", std::uint64_t(p.view().size()))
      .add("visible_entities_mean", p.meanVisible())
      .add("ghosts", std::uint64_t(p.ghosts(now)))
      .add("unspawned", std::uint64_t(p.unspawned()));
  // Where it shows its own avatar: a flyer at its kind's height, a walker on the ground.
  if (auto self = p.ownPosition(now)) j.add("avatar_y", self->y);
  addLink(j, p.impairment());
  return j.str();
}

// The fleet's transaction channels together (clients/transaction_stream.h).
std::string transactionsJson(const std::vector<std::unique_ptr<SimPlayer>>& players) {
  TransactionCounters t;
  std::uint64_t pending = 0;
  for (const auto& p : players) {
    const TransactionCounters& c = p->transactionCounters();
    t.made += c.made;
    t.sent += c.sent;
    t.resent += c.resent;
    t.committed += c.committed;
    t.already_committed += c.already_committed;
    t.conflicts += c.conflicts;
    t.failed += c.failed;
    t.outcome_repeats += c.outcome_repeats;
    t.outcome_unknown += c.outcome_unknown;
    t.refused_window_full += c.refused_window_full;
    t.latency_ms.merge(c.latency_ms);
    pending += p->pendingTransactions();
  }
  JsonLine j;
  j.add("made", t.made)
      .add("sent", t.sent)
      .add("resent", t.resent)
      .add("committed", t.committed)
      .add("already_committed", t.already_committed)
      .add("conflicts", t.conflicts)
      .add("failed", t.failed)
      .add("pending", pending)
      .add("outcome_repeats", t.outcome_repeats)
      .add("outcome_unknown", t.outcome_unknown)
      .add("refused_window_full", t.refused_window_full)
      .add("latency_ms_p50", percentile(t.latency_ms.samples(), 50))
      .add("latency_ms_p99", percentile(t.latency_ms.samples(), 99))
      .add("latency_ms_max", t.latency_ms.max());
  return j.str();
}

}  // namespace

PlayerCounters totalCounters(const std::vector<std::unique_ptr<SimPlayer>>& players, bool samples) {
  PlayerCounters t;
  for (const auto& p : players) addSum(t, p->counters(), samples);
  return t;
}

JsonLine fleetMetricsLine(const std::vector<std::unique_ptr<SimPlayer>>& players, double t,
                          const PlayerCounters& now, const PlayerCounters& before,
                          double interval_s) {
  std::uint64_t visible = 0, welcomed = 0;
  std::vector<double> latest_rtt;
  for (const auto& p : players) {
    visible += p->view().size();
    welcomed += p->welcomed() ? 1 : 0;
    if (p->counters().rtt_ms.seen() > 0) latest_rtt.push_back(p->counters().last_rtt_ms);
  }
  JsonLine j;
  j.add("t", t)
      .add("players", std::uint64_t(players.size()))
      .add("welcomed", welcomed)
      .add("visible_entities", visible)
      .add("bytes_in", now.bytes_in)
      .add("bytes_out", now.bytes_out)
      .add("datagrams_in", now.datagrams_in)
      .add("datagrams_out", now.datagrams_out)
      .add("updates", now.updates)
      .add("spawns", now.spawns)
      .add("despawns", now.despawns)
      .add("handoffs", now.handoffs)
      .add("dropped", now.drops.total())
      .add("bytes_in_per_s", rate(now.bytes_in - before.bytes_in, interval_s))
      .add("bytes_out_per_s", rate(now.bytes_out - before.bytes_out, interval_s))
      .add("updates_per_s", rate(now.updates - before.updates, interval_s))
      .add("rtt_ms_p50", percentile(latest_rtt, 50));
  return j;
}

double cpuUsPerPlayerSecond(const FleetCost& cost, std::size_t players) {
  if (players == 0 || cost.run_s <= 0) return 0;
  return cost.cpu_s * 1e6 / (double(players) * cost.run_s);
}

double wakeupsPerSecond(const FleetCost& cost) {
  return rate(cost.wakeups, cost.run_s);
}

std::string fleetSummaryJson(const std::vector<std::unique_ptr<SimPlayer>>& players,
                             double duration_s, const FleetCost& cost,
                             double started_monotonic_s) {
  std::string list = "[";
  std::uint64_t visible = 0, welcomed = 0;
  for (std::size_t i = 0; i < players.size(); ++i) {
    if (i > 0) list += ',';
    list += clientJson(*players[i], duration_s);
    visible += players[i]->view().size();
    welcomed += players[i]->welcomed() ? 1 : 0;
  }
  list += ']';
  JsonLine totals;
  totals.add("welcomed", welcomed);
  addTraffic(totals, totalCounters(players, true), duration_s);
  totals.add("visible_entities", visible);
  JsonLine j;
  j.add("players", std::uint64_t(players.size()))
      .add("duration_s", duration_s)
      .add("started_monotonic_s", started_monotonic_s)
      .add("fleet_cpu_s", cost.cpu_s)
      .add("fleet_process_cpu_s", cost.process_cpu_s)
      .add("fleet_cpu_us_per_player_s", cpuUsPerPlayerSecond(cost, players.size()))
      .add("fleet_wakeups_per_s", wakeupsPerSecond(cost))
      .addRaw("clients", list)
      .addRaw("totals", totals.str())
      .addRaw("transactions", transactionsJson(players))
      .addRaw("kinds", kindsSummaryJson(players, duration_s));
  return j.str();
}

}  // namespace zonesim::clients
