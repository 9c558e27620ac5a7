#include "zone_node/zone_report.h"

#include <unistd.h>

#include <algorithm>

#include "common/stats.h"
#include "zone_node/systems/duels.h"
#include "zone_node/transactions.h"

namespace zonesim::zone {

namespace {
std::string hostName() {
  char name[256] = {};
  return gethostname(name, sizeof name - 1) == 0 ? std::string(name) : std::string();
}

// {"1":12,"3":4}: a JSON object keyed by rank.
// The zone's duels (scene key `adaptation`): win rates by skill, and where each NPC ended.
std::string duelsJson(const std::vector<DuelFigures>& duels) {
  std::string out;
  for (const DuelFigures& d : duels) {
    JsonLine j;
    j.add("duel", std::uint64_t(d.index)).add("skill", d.skill);
    j.add("rounds", d.rounds).add("player_wins", d.player_wins);
    j.add("win_rate", d.rounds ? double(d.player_wins) / double(d.rounds) : 0.0);
    j.add("npc_accuracy", d.npc.accuracy).add("npc_aggression", d.npc.aggression);
    j.add("npc_reaction_steps", d.npc.reaction_steps);
    j.add("guard_fallbacks", d.guard.fallbacks).add("guard_clamped", d.guard.clamped);
    j.add("guard_rate_limited", d.guard.rate_limited);
    out += (out.empty() ? "" : ",") + j.str();
  }
  return "[" + out + "]";
}

std::string byRank(const std::map<int, std::uint64_t>& counts) {
  std::string out;
  for (const auto& [rank, n] : counts)
    out += (out.empty() ? "\"" : ",\"") + std::to_string(rank) + "\":" + std::to_string(n);
  return "{" + out + "}";
}
}  // namespace

ZoneReport::ZoneReport(const ZoneNode& zone) : entities_start_(zone.store().size()) {
  // As a checkpoint's manifest sums it over the ranks: a restart can be checked against it.
  IdSetDigest start;
  for (EntityId id : zone.store().id) start.add(id);
  id_hash_start_ = start.hash;
}

void ZoneReport::recordPacing(const ZoneNode& zone, double period_seconds, bool late) {
  if (zone.lastTickFactor() < 1) dilated_wall_s_ += period_seconds;
  late_ = late;
  late_ticks_ += late ? 1 : 0;
}

void ZoneReport::recordTick(const ZoneNode& zone, double tick_seconds, MetricsWriter& metrics) {
  tick_ms_.push_back(tick_seconds * 1e3);
  factor_ = zone.lastTickFactor();
  min_factor_ = std::min(min_factor_, factor_);
  dilated_ticks_ += factor_ < 1 ? 1 : 0;
  const TickProfile& p = zone.profile();
  for (std::size_t i = 0; i < kPhaseCount; ++i) phase_totals_.seconds[i] += p.seconds[i];
  for (std::size_t i = 0; i < kStageCount; ++i)
    phase_totals_.stage_seconds[i] += p.stage_seconds[i];
  for (const CompletedHandoff& h : zone.handoffsCompleted())
    handoff_latency_ms_.push_back(double(h.ticks) * zone.tickSeconds() * 1e3);
  for (const Departure& d : zone.migratedThisTick()) {
    if (d.to_rank < 0) continue;
    ++migrated_to_[d.to_rank];
    if (d.announced_avatar) ++avatars_to_[d.to_rank];
  }
  const TickCounters& c = zone.counters();
  for (const CounterField& f : kCounterFields)
    totals_.*f.field = f.gauge ? c.*f.field : totals_.*f.field + c.*f.field;
  if (!metrics.enabled()) return;
  JsonLine line;
  line.add("tick", zone.tickCount())
      .add("rank", zone.rank())
      .add("entities", std::uint64_t(zone.store().size()));
  line.add("tick_ms", tick_seconds * 1e3);
  line.add("dilation", factor_).add("wall_s", since_start_.elapsedSeconds());
  line.add("late", std::uint64_t(late_ ? 1 : 0));
  late_ = false;
  for (std::size_t i = 0; i < kPhaseCount; ++i)
    line.add(std::string(kPhaseNames[i]) + "_ms", p.seconds[i] * 1e3);
  for (std::size_t i = 0; i < kStageCount; ++i)
    line.add(std::string(kStageNames[i]) + "_ms", p.stage_seconds[i] * 1e3);
  for (const CounterField& f : kCounterFields) line.add(f.name, c.*f.field);
  metrics.write(line);
}

std::string ZoneReport::summaryJson(const ZoneNode& zone, double wall_seconds) const {
  const ZoneRect r = zone.layout().rect(zone.rank());
  JsonLine s;
  s.add("rank", zone.rank()).add("ranks", zone.size()).add("ticks", zone.tickCount());
  s.add("host", hostName());  // which rank ran where, for runs across hosts
  s.addRaw("rect", "[" + std::to_string(r.min_x) + "," + std::to_string(r.min_z) + "," +
                       std::to_string(r.max_x) + "," + std::to_string(r.max_z) + "]");
  s.add("entities_start", entities_start_).add("entities_end", std::uint64_t(zone.store().size()));
  s.add("id_hash_start", id_hash_start_).add("epoch", std::uint64_t(zone.epoch()));
  s.add("wall_s", wall_seconds);
  s.add("tick_ms_p50", percentile(tick_ms_, 50)).add("tick_ms_p99", percentile(tick_ms_, 99));
  s.add("tick_ms_max", percentile(tick_ms_, 100));
  double n = tick_ms_.empty() ? 1.0 : double(tick_ms_.size());
  for (std::size_t i = 0; i < kPhaseCount; ++i)
    s.add(std::string(kPhaseNames[i]) + "_ms_mean", phase_totals_.seconds[i] * 1e3 / n);
  for (std::size_t i = 0; i < kStageCount; ++i)
    s.add(std::string(kStageNames[i]) + "_ms_mean", phase_totals_.stage_seconds[i] * 1e3 / n);
  for (const CounterField& f : kCounterFields) s.add(f.name, totals_.*f.field);
  s.add("conservation_checks", zone.conservation().checks);
  s.add("conservation_failures", zone.conservation().failures);
  s.add("mail_failures", zone.conservation().mail_failures);
  s.add("mail_posted_cluster", zone.conservation().last_mail_posted);
  s.add("dilation_min", min_factor_).add("dilation_changes", zone.dilation().changes());
  s.add("dilated_ticks", dilated_ticks_).add("dilated_wall_s", dilated_wall_s_);
  s.add("late_ticks", late_ticks_);
  s.add("particle_backend", zone.particleBackend());
  s.add("flock_backend", zone.flockBackend());
  const std::vector<DuelFigures> duels = zone.duelFigures();
  if (!duels.empty()) s.addRaw("duels", duelsJson(duels));
  s.addRaw("migrated_out_to", byRank(migrated_to_));
  s.addRaw("avatars_out_to", byRank(avatars_to_));
  const TransactionCounters& t = zone.transactions().counters();
  s.add("transactions_received", t.received).add("transactions_submitted", t.submitted);
  s.add("transactions_resubmitted", t.resubmitted)
      .add("transactions_answered_again", t.answered_again);
  s.add("transactions_not_here", t.not_here).add("transactions_too_far", t.too_far);
  s.add("transactions_gap_notices", t.gap_notices)
      .add("transactions_fast_forwards", t.fast_forwards);
  s.add("transactions_committed", t.committed)
      .add("transactions_already_committed", t.already_committed);
  s.add("transactions_conflicts", t.conflicts).add("transactions_failed", t.failed);
  s.add("ledger_batches", zone.transactions().ledgerStats().batches);
  s.add("leaderboards_answered", zone.leaderboardsAnswered());
  s.add("handoffs_timed", std::uint64_t(handoff_latency_ms_.size()));
  if (!handoff_latency_ms_.empty()) {
    s.add("handoff_latency_ms_p50", percentile(handoff_latency_ms_, 50))
        .add("handoff_latency_ms_p99", percentile(handoff_latency_ms_, 99))
        .add("handoff_latency_ms_max", percentile(handoff_latency_ms_, 100));
    std::string all;  // every sample, for distributions over many runs
    for (double ms : handoff_latency_ms_) all += (all.empty() ? "" : ",") + std::to_string(ms);
    s.addRaw("handoff_latency_ms", "[" + all + "]");
  }
  return s.str();
}

}  // namespace zonesim::zone
