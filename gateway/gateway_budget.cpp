// The gateway under a downlink budget: what of a player's view diff goes out this tick
// (budgetDiff), within the tokens of its DownlinkBudget (gateway/downlink_budget.h), sized by
// encoding exactly what would be sent (fitting, fittingDespawns). The rest waits in the view.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "gateway/gateway.h"

namespace zonesim::gateway {

namespace {
// Under a budget, the view radius never narrows below this fraction of the nimbus.
constexpr double kLeastViewFraction = 0.25;

// The largest k <= n for which fits(k) holds, fits being true up to some k and false after
// (sizes grow with the prefix): a binary search, about log2(n) encodings.
template <typename Fits>
std::size_t longestFittingPrefix(std::size_t n, Fits fits) {
  std::size_t lo = 0, hi = n;
  while (lo < hi) {
    std::size_t mid = (lo + hi + 1) / 2;
    if (fits(mid))
      lo = mid;
    else
      hi = mid - 1;
  }
  return lo;
}

}  // namespace

void Gateway::fitting(const Session& s, const Fit& forced,
                      const std::vector<std::pair<std::uint64_t, bool>>& ranked, double available,
                      Fit& out) const {
  // Encodes exactly what sendView will send (seq is a fixed-width field, the batch tick the
  // newest of the set), so the size measured here is the size sent. Candidates are built in
  // kept buffers: this runs a binary search for every player every send.
  auto take = [&](std::size_t k, Fit& f) -> const Fit& {
    f.spawns.assign(forced.spawns.begin(), forced.spawns.end());
    f.updates.assign(forced.updates.begin(), forced.updates.end());
    for (std::size_t i = 0; i < k; ++i)
      (ranked[i].second ? f.spawns : f.updates).push_back(ranked[i].first);
    std::sort(f.spawns.begin(), f.spawns.end());
    std::sort(f.updates.begin(), f.updates.end());
    return f;
  };
  auto bytes = [&](const std::vector<std::uint64_t>& ids, bool spawns) {
    if (ids.empty()) return std::size_t{0};
    std::uint64_t tick = encodedStates(ids, sizing_states_);
    std::size_t n =
        spawns
            ? encodeSpawnFrames(s.token, tick, codec_, sizing_states_, sizingSeq(), sizing_frames_)
            : encodeStateFrames(s.token, tick, codec_, sizing_states_, sizingSeq(), sizing_frames_);
    return totalBytes(sizing_frames_, n);
  };
  auto size = [&](const Fit& f) { return bytes(f.spawns, true) + bytes(f.updates, false); };
  // Forced traffic goes as debt: what the rest adds to it must fit.
  double base = double(size(forced));
  take(longestFittingPrefix(
           available > 0 ? ranked.size() : 0,
           [&](std::size_t k) { return double(size(take(k, sizing_fit_))) - base <= available; }),
       out);
}

std::size_t Gateway::despawnBytes(const Session& s, std::span<const std::uint64_t> ids) const {
  if (ids.empty()) return 0;
  return totalBytes(sizing_frames_,
                    encodeDespawnFrames(s.token, clock_.tick(), ids, sizingSeq(), sizing_frames_));
}

std::size_t Gateway::fittingDespawns(const Session& s, const std::vector<std::uint64_t>& ids,
                                     double available, std::size_t& bytes) const {
  // The longest prefix is the largest k found to fit, so its size is known from the search.
  std::size_t best = 0;
  bytes = 0;
  return longestFittingPrefix(ids.size(), [&](std::size_t k) {
    std::size_t b = despawnBytes(s, std::span(ids).first(k));
    if (double(b) > available) return false;
    if (k > best) best = k, bytes = b;
    return true;
  });
}

void Gateway::budgetDiff(Session& s, ViewDiff& diff, const ViewPoint& at, double nimbus,
                         std::int64_t now_ns) {
  const DeadReckoning& drs = config_.scene.dead_reckoning;
  // The zone's own thresholds are the floor: nearer than floor / angle, every state the zone
  // sent is worth sending, so the near band keeps the zone's precision.
  double floor = std::max(drs.position_threshold, 1e-6);
  double rot_floor = std::max(drs.orientation_threshold_deg * M_PI / 180.0, 1e-6);
  auto distanceOf = [&](std::uint64_t id) {
    dr::V3 p = predictedPosition(*cache_.find(id), at.sim_now);
    return std::hypot(p.x - at.x, p.z - at.z);
  };
  // Despawns go first, as far as the tokens reach, full bucket or not; the rest stay in the
  // view and are listed again next tick. A client shows a departed entity a few ticks longer
  // rather than the budget overrun: a view that narrows or a walk out of a town of resting
  // bodies can leave hundreds at once.
  double tokens = s.budget.tokens();
  if (!diff.despawns.empty()) {
    std::size_t bytes = 0;
    std::size_t fit = fittingDespawns(s, diff.despawns, std::max(tokens, 0.0), bytes);
    for (std::size_t i = fit; i < diff.despawns.size(); ++i) {
      s.view.holdDespawn(diff.despawns[i]);
      ++s.traffic.deferred;
      ++counters_.deferred;
    }
    diff.despawns.resize(fit);
    tokens -= double(bytes);
  }
  // Until the bucket is full, only guaranteed traffic goes (the rest waits, gathered).
  double available = s.budget.tokens() >= budget_send_bytes_ ? tokens : 0.0;
  // The avatar goes in every send (and a state whose reference the budget never saw). Then,
  // in three ranks: updates of the near band (where angle * distance is within the zone's
  // threshold), so that what is shown near stays current while a view fills in; spawns of
  // the near band; the rest. Within each, by accumulated priority: spawns as an entity
  // missing by kMissingEntityM, updates by the error the client shows, both as angles at the
  // viewer. Near spawns are not starved: a near update that waits narrows the view until the
  // near updates leave room.
  auto nearBand = [&](double d) { return config_.budget.error_angle_rad * d <= floor; };
  enum Rank { kNearUpdate, kNearSpawn, kFar };
  // Kept buffers: this runs for every player every tick.
  Fit& forced = budget_forced_;
  forced.spawns.clear();
  forced.updates.clear();
  auto& order = budget_order_;  // band, -priority, id, spawn
  order.clear();
  for (std::uint64_t id : diff.spawns) {
    if (id == at.self) {
      forced.spawns.push_back(id);
      continue;
    }
    double d = distanceOf(id);
    double acc = s.budget.accumulateSpawn(id, errorPriority(kMissingEntityM, d));
    order.emplace_back(nearBand(d) ? kNearSpawn : kFar, -acc, id, true);
  }
  for (std::uint64_t id : diff.updates) {
    const CachedEntity* sent = s.budget.lastSent(id);
    // The avatar's own state rides with each send rather than in a datagram of its own every
    // tick (30 frames a second of 13 B framing each: 390 of 20 kbit/s's 2,500 B/s before any
    // record): it waits at most ticksPerSend - 1 ticks.
    if (id == at.self && sent != nullptr && available <= 0) {
      s.view.defer(id);
      continue;
    }
    if (id == at.self || sent == nullptr) {
      forced.updates.push_back(id);
      continue;
    }
    double d = distanceOf(id);
    double limit = std::max(floor, config_.budget.error_angle_rad * d);
    ShownError err = shownError(*sent, *cache_.find(id), at.sim_now);
    // Orientation error counted as the position error it is worth (floor per rot_floor).
    double error = std::max(err.position, err.orientation * floor / rot_floor);
    bool near = nearBand(d);
    bool heartbeat = at.sim_now - sent->sim_time >= drs.heartbeat_seconds;
    if (!near && !heartbeat && error <= limit) {
      s.view.defer(id);
      ++s.traffic.held;
      ++counters_.held;
      continue;
    }
    double acc = s.budget.accumulate(id, errorPriority(std::max(error, floor), d));
    order.emplace_back(near ? kNearUpdate : kFar, -acc, id, false);
  }
  std::sort(order.begin(), order.end());
  std::vector<std::pair<std::uint64_t, bool>>& ranked = budget_ranked_;
  ranked.clear();
  for (auto& [band, key, id, spawn] : order) ranked.emplace_back(id, spawn);
  Fit& go = budget_go_;
  fitting(s, forced, ranked, available, go);
  // How many of ranked went (a prefix: fitting takes the longest that fits).
  std::size_t taken =
      go.spawns.size() + go.updates.size() - forced.spawns.size() - forced.updates.size();
  // On a send, the view narrows while a near update could not go, or what it ranked and could
  // not carry is a long backlog for the budget's rate, and widens again when not; never below
  // a quarter of the nimbus.
  if (available > 0) {
    std::size_t waiting_near = 0;
    for (std::size_t i = taken; i < order.size(); ++i)
      if (std::get<0>(order[i]) == kNearUpdate) ++waiting_near;
    bool pressed = s.budget.pressed(taken, ranked.size() - taken, waiting_near, available,
                                    config_.budget.bytesPerSecond());
    s.budget.adaptRadius(pressed, nimbus, nimbus * kLeastViewFraction,
                         s.budget.secondsSinceAdapt(now_ns));
  }
  // What did not fit waits: listed again next tick. A spawn never sent is forgotten (the
  // client does not hold it); one sent but unacknowledged stays known, so that a despawn
  // still follows if it leaves the view before its resend gets through.
  for (std::size_t i = taken; i < ranked.size(); ++i) {
    auto [id, spawn] = ranked[i];
    if (spawn && !s.resend.spawnPending(id))
      s.view.forget(id);
    else
      s.view.defer(id);
    ++s.traffic.deferred;
    ++counters_.deferred;
  }
  diff.spawns.swap(go.spawns);  // swapped, so both keep their storage
  diff.updates.swap(go.updates);
}

}  // namespace zonesim::gateway
