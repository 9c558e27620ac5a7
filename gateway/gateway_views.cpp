// The gateway's per-tick views: each player's visible set against what it holds (sendViews),
// resends merged in (addResends), and the despawns, spawns and updates sent as lean frames
// (sendView). Under a budget, gateway_budget.cpp decides what of the diff goes.
#include <algorithm>

#include "gateway/gateway.h"

namespace zonesim::gateway {

void Gateway::sendViews(std::int64_t now_ns) {
  double sim_now = clock_.simNow(now_ns);
  encoded_.clear();  // the cache took this tick's samples: every state is encoded anew
  // The bucket fills by the time that passed, not by the tick: a gateway that falls behind its
  // cadence (an overloaded machine) still hands each player its budget. At most a send's worth
  // of ticks at once, so the bound on every 1 s window holds as at the nominal cadence.
  double refill_ticks = last_views_ns_ > 0
                            ? std::clamp(double(now_ns - last_views_ns_) / double(tick_ns_), 0.0,
                                         double(budget_ticks_per_send_))
                            : 1.0;
  last_views_ns_ = now_ns;
  ++views_;
  const bool record_views = recorder_ && views_ % std::uint64_t(config_.record_every_ticks) == 0;
  snapshot_.rebuild(cache_, grid_, sim_now);
  sessions_.forEach([&](SlotHandle, Session& s) {
    if (!s.welcomed) return;
    ViewPoint at;
    avatarPosition(s, sim_now, at.x, at.z);
    const AuraNimbus& an = config_.scene.aura_nimbus;
    double nimbus = nimbusOf(s);
    // Under a budget the view may be narrowed (DownlinkBudget::adaptRadius).
    at.nimbus = config_.budget.enabled() ? std::min(nimbus, s.budget.viewRadius()) : nimbus;
    at.keep = at.nimbus * 1.1;
    at.aura = {an.npc, an.avatar, an.rigid_body, an.emitter, an.item};
    at.self = s.avatar_id;
    const CachedEntity* self = s.avatar_id != 0 ? cache_.find(s.avatar_id) : nullptr;
    at.self_version = self != nullptr ? self->version : 0;
    at.sim_now = sim_now;
    ViewDiff& diff = diff_;
    // A player's full scan falls on its own tick of every full_scan_every_ticks (by token, so
    // the scans spread over the ticks); the avatar's first appearance does not wait.
    std::uint64_t every = std::uint64_t(config_.full_scan_every_ticks);
    bool full_scan = config_.budget.enabled() || every <= 1 || (views_ + s.token) % every == 0 ||
                     !s.view.knows(s.avatar_id);
    if (full_scan) {
      selectVisible(snapshot_, grid_, at, s.view, visible_);
      s.view.diff(visible_, diff);
    } else {
      selectChanged(snapshot_, grid_, at, s.view, visible_);
      s.view.diffKnown(visible_, diff);
    }
    if (config_.budget.enabled())
      s.budget.refill(budget_bytes_per_tick_ * refill_ticks, budget_cap_bytes_);
    if (config_.resend) {
      addResends(s, diff, now_ns);
      resendHandoff(s, now_ns);
    }
    if (config_.budget.enabled()) budgetDiff(s, diff, at, nimbus, now_ns);
    std::uint64_t tick = clock_.tick();
    if (!diff.empty()) {
      sendView(s, diff, now_ns);
      s.told_tick = std::max(s.told_tick, tick);
    } else if (config_.clock_every_ticks > 0 &&
               tick >= s.told_tick + std::uint64_t(config_.clock_every_ticks)) {
      sendTo(s, encodeClockTick(s.token, tick));
      s.told_tick = tick;
      ++counters_.clock_ticks;
    }
    if (config_.budget.enabled()) s.budget.endTick();
    if (record_views) recordView(s, at);
  });
  if (record_views) recordTick(sim_now);
}

void Gateway::addResends(Session& s, ViewDiff& diff, std::int64_t now_ns) {
  ResendDue& due = due_;
  s.resend.due(now_ns, config_.loss_detection, due);
  std::size_t before = diff.spawns.size() + diff.updates.size() + diff.despawns.size();
  // Resends carry the newest state; only what the view still holds (or no longer holds, for a
  // despawn) is worth sending: a newer spawn or despawn of the same id supersedes it.
  auto merge = [&](std::vector<std::uint64_t>& into, const std::vector<std::uint64_t>& more,
                   bool check, bool known) {
    std::size_t n = into.size();
    for (std::uint64_t id : more)
      if (!check || (s.view.knows(id) == known && (!known || cache_.find(id) != nullptr)))
        into.push_back(id);
    if (into.size() == n) return;
    std::sort(into.begin(), into.end());
    into.erase(std::unique(into.begin(), into.end()), into.end());
  };
  // A state of an entity whose spawn is unacknowledged goes as a Spawn: the client may not
  // know it yet and would drop a bare update.
  std::vector<std::uint64_t>& as_spawn = scratch_ids_;
  as_spawn.clear();
  std::erase_if(diff.updates, [&](std::uint64_t id) {
    if (!s.resend.spawnPending(id)) return false;
    as_spawn.push_back(id);
    return true;
  });
  merge(diff.spawns, as_spawn, false, true);
  merge(diff.spawns, due.spawns, true, true);
  merge(diff.updates, due.updates, true, true);
  merge(diff.despawns, due.despawns, true, false);
  std::size_t after = diff.spawns.size() + diff.updates.size() + diff.despawns.size();
  s.traffic.resent += after - before;
  counters_.resent += after - before;
}

void Gateway::sendView(Session& s, const ViewDiff& diff, std::int64_t now_ns) {
  // States go out as the zones sampled them, with their tick: the client runs the same model
  // from the same state, so nothing is extrapolated here.
  std::uint64_t tick = clock_.tick();
  // Every datagram gets the session's next seq (consecutive within one encoding); the tracker
  // learns which ids each one held. The buffers are the gateway's, reused for every player.
  ChunkSeq seq{[](void* t) { return static_cast<ResendTracker*>(t)->nextSeq(); }, &s.resend,
               &chunk_counts_};
  auto send = [&](std::uint32_t first, std::size_t frames, const std::vector<std::uint64_t>& ids,
                  Carried what, std::uint64_t batch_tick = 0) {
    std::size_t at = 0;
    for (std::size_t i = 0; i < frames; ++i) {
      sendTo(s, frames_.frames[i]);
      if (config_.resend)
        s.resend.sent(first + std::uint32_t(i), std::span(ids).subspan(at, chunk_counts_[i]), what,
                      now_ns);
      at += chunk_counts_[i];
    }
    if (recorder_) {
      std::span<const Bytes> sent(frames_.frames.data(), frames);
      if (what == Carried::Despawn)
        recorder_->despawnFrames(s.player_id, sent, chunk_counts_, ids);
      else
        recorder_->stateFrames(s.player_id, sent, chunk_counts_, encoded_scratch_, batch_tick,
                               what == Carried::Spawn);
    }
    chunk_counts_.clear();
  };
  std::vector<dr::EncodedEntity>& states = encoded_scratch_;
  std::uint32_t first = s.resend.upcoming();
  send(first, encodeDespawnFrames(s.token, tick, diff.despawns, seq, frames_), diff.despawns,
       Carried::Despawn);
  first = s.resend.upcoming();
  std::uint64_t batch = encodedStates(diff.spawns, states);
  send(first, encodeSpawnFrames(s.token, batch, codec_, states, seq, frames_), diff.spawns,
       Carried::Spawn, batch);
  first = s.resend.upcoming();
  batch = encodedStates(diff.updates, states);
  send(first, encodeStateFrames(s.token, batch, codec_, states, seq, frames_), diff.updates,
       Carried::Update, batch);
  if (config_.budget.enabled()) {
    for (std::uint64_t id : diff.despawns) s.budget.forget(id);
    for (std::uint64_t id : diff.spawns) s.budget.sent(id, *cache_.find(id));
    for (std::uint64_t id : diff.updates) s.budget.sent(id, *cache_.find(id));
  }
  s.traffic.despawns_sent += diff.despawns.size();
  s.traffic.spawns_sent += diff.spawns.size();
  s.traffic.updates_sent += diff.updates.size();
  counters_.despawns_sent += diff.despawns.size();
  counters_.spawns_sent += diff.spawns.size();
  counters_.updates_forwarded += diff.updates.size();
}

std::uint64_t Gateway::encodedStates(const std::vector<std::uint64_t>& ids,
                                     std::vector<dr::EncodedEntity>& out) const {
  // Every encoding is made before any is pointed at: an insertion may move the map's slots.
  for (std::uint64_t id : ids)
    if (!encoded_.contains(id))
      encoded_.insertOrAssign(id, codec_.encodeState(wireEntity(*cache_.find(id))));
  out.clear();
  std::uint64_t newest = clock_.tick();
  for (std::uint64_t id : ids) {
    std::uint64_t tick = cache_.find(id)->tick;
    out.push_back({id, tick, encoded_.find(id)});
    newest = std::max(newest, tick);
  }
  return newest;
}

}  // namespace zonesim::gateway
