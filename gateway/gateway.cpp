#include "gateway/gateway.h"

#include <poll.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <random>
#include <stdexcept>
#include <system_error>
#include <tuple>

#include "common/log.h"
#include "common/timer.h"

namespace zonesim::gateway {

namespace {
constexpr std::int64_t kSecondNs = 1'000'000'000;
// Bounded so a flood of datagrams cannot starve the tick.
constexpr int kMaxDatagramsPerWake = 4096;
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

std::int64_t seconds(double s) {
  return std::int64_t(s * 1e9);
}

HandlerConfig handlerConfig(const GatewayConfig& c) {
  HandlerConfig h{c.scene.world, float(c.scene.tick_rate), c.spawn_seed, dr::codecParams(c.scene),
                  float(c.scene.dt)};
  h.auth_key = c.auth_key;
  h.gateway_id = std::uint16_t(c.gateway_id);
  h.kinds = 0;
  for (const PlayerKind& k : playerKinds(c.scene.clients)) h.kinds |= std::uint32_t{1} << int(k.id);
  return h;
}

/// A random non-zero 16-bit number per gateway process: player ids of a restarted gateway (and
/// of gateways left at the same --gateway-id) differ from the ones the zones already saw.
std::uint16_t randomIncarnation() {
  std::random_device rd;
  return std::uint16_t(1 + rd() % 0xFFFF);
}

std::int64_t graceNs(const GatewayConfig& c) {
  if (c.handoff_grace_s > 0) return seconds(c.handoff_grace_s);
  // Long enough for a new cell writer of the receiving zone to be discovered even on a loaded
  // machine; a removal waits this long, a handoff never shows as despawn + spawn.
  return std::max(seconds(2.0 / c.scene.tick_rate), seconds(0.25));
}

int expectedZones(const GatewayConfig& c) {
  return c.expected_zones > 0 ? c.expected_zones : c.scene.zones.columns * c.scene.zones.rows;
}

double interestRadius(const GatewayConfig& c) {
  // The visibility keep radius (nimbus * 1.1) plus a margin ahead of motion, of the kind that
  // reaches farthest (each player's update gives its own).
  double r = 0;
  for (const PlayerKind& k : playerKinds(c.scene.clients))
    r = std::max(r, k.nimbus * 1.1 + k.speed * c.lookahead_s);
  return r;
}

/// The scene's kinds by id; a kind the scene lacks keeps the default (no session has it: the
/// handler refuses its Hello).
std::array<PlayerKind, kPlayerKindCount> kindTable(const Scene& scene) {
  std::array<PlayerKind, kPlayerKindCount> table{};
  for (const PlayerKind& k : playerKinds(scene.clients)) table[std::size_t(k.id)] = k;
  return table;
}
}  // namespace

Gateway::Gateway(GatewayConfig config)
    : config_(std::move(config)),
      grid_(config_.scene.world, config_.scene.interest_cell_size),
      tick_ns_(std::max<std::int64_t>(1, seconds(1.0 / config_.scene.tick_rate))),
      start_ns_(nowNs()),
      socket_(config_.bind),
      sessions_(config_.gateway_id, config_.max_sessions, randomIncarnation()),
      handler_(sessions_, handlerConfig(config_)),
      cache_(graceNs(config_)),
      clock_(config_.scene.tick_rate * config_.scene.dt),
      interest_(grid_, interestRadius(config_), grid_.cell_size() * 0.5),
      kinds_(kindTable(config_.scene)),
      link_(config_.dds_domain, expectedZones(config_)),
      rx_batch_(kMaxDatagramBytes + 1),
      codec_(dr::codecParams(config_.scene)),
      impairment_(config_.impairment, 0x9a7e) {
  if (!config_.metrics_path.empty()) metrics_ = MetricsWriter(config_.metrics_path);
  if (config_.auth_key) {
    LoadIdentity id{std::uint16_t(config_.gateway_id), randomIncarnation(),
                    publicAddress(config_.public_address, socket_.local()),
                    std::uint32_t(config_.max_sessions)};
    load_report_.emplace(link_.participant(), link_.topics().gateway_load.get(), id);
    load_report_->publish(0, 0);  // known to the lobby before the first player asks
  }
  checkBudget(config_.budget, 0, config_.budget_names.first, config_.budget_names.second);
  if (config_.budget.enabled()) {
    // The least a second must carry: one spawn of the largest record (second order, rotating).
    dr::WireEntity widest;
    widest.id = ~std::uint64_t{0} >> 1;
    widest.model = {dr::Order::Second, dr::Spin::Rotating};
    std::size_t one_spawn = totalBytes(encodeSpawnChunks(~std::uint64_t{0}, ~std::uint64_t{0} >> 1,
                                                         codec_, {&widest, 1}, sizingSeq()));
    checkBudget(config_.budget, one_spawn, config_.budget_names.first, config_.budget_names.second);
    budget_bytes_per_tick_ = config_.budget.bytesPerTick(config_.scene.tick_rate);
    // Spawns and updates go when the bucket holds a send's worth (ticksPerSend ticks' bytes,
    // or one spawn datagram where that is more); guaranteed traffic goes every tick. The
    // bucket holds a tick more than a send, so a send that waits for the next tick's bytes
    // loses none of them to the cap.
    budget_ticks_per_send_ = config_.budget.ticksPerSend(config_.scene.tick_rate);
    budget_send_bytes_ =
        std::max(budget_bytes_per_tick_ * budget_ticks_per_send_, double(one_spawn));
    budget_cap_bytes_ = budget_send_bytes_ + budget_bytes_per_tick_;
  }
  if (config_.full_scan_every_ticks < 1)
    throw std::invalid_argument("gateway: --full-scan-every must be at least 1, not " +
                                std::to_string(config_.full_scan_every_ticks));
  // The gateway handles each datagram as it arrives: it can lose incoming ones, not hold them.
  if (!config_.impairment.in.lossOnly())
    throw std::invalid_argument("gateway: incoming impairment can only lose datagrams, not '" +
                                config_.impairment.in.name + "'");
}

void Gateway::run(const std::atomic<bool>& stop, double duration_s) {
  start_ns_ = nowNs();
  start_process_cpu_ns_ = processCpuNs();
  std::int64_t end_ns = duration_s > 0 ? start_ns_ + seconds(duration_s) : INT64_MAX;
  std::int64_t next_tick = start_ns_;
  next_metrics_ns_ = start_ns_ + kSecondNs;
  while (!stop.load(std::memory_order_relaxed)) {
    std::int64_t now = nowNs();
    if (now >= end_ns) break;
    if (now >= next_tick) {
      tick(now);
      next_tick += tick_ns_;
      // After a stall, resume the cadence from now instead of bursting to catch up.
      if (next_tick <= now) next_tick = now + tick_ns_;
    }
    if (impairment_.active()) counters_.send_failures += impairment_.flush(socket_, nowNs());
    pollfd p{socket_.fd(), POLLIN, 0};
    if (pollUntil({&p, 1}, std::min({next_tick, end_ns, impairment_.nextDueNs()})) > 0)
      receiveAll(nowNs());
  }
  writeMetrics(nowNs());
  metrics_.flush();
}

void Gateway::receiveAll(std::int64_t now_ns) {
  for (int taken = 0; taken < kMaxDatagramsPerWake;) {
    std::size_t n = rx_batch_.receive(socket_);
    if (n == 0) break;
    taken += int(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Received& got = rx_batch_.received(i);
      ++counters_.datagrams_in;
      counters_.bytes_in += got.size;
      if (impairment_.active() && impairment_.dropIncoming()) continue;
      // The buffers hold kMaxDatagramBytes + 1: anything that filled one is over the limit.
      if (got.truncated || got.size > kMaxDatagramBytes) {
        handler_.countTooLarge();
        continue;
      }
      handler_.handle(rx_batch_.bytes(i), got.from, now_ns, outbox_);
    }
  }
  carryOut(outbox_);
  flushSends();
}

void Gateway::flushSends() {
  if (send_queue_.empty()) return;
  FlushResult r = send_queue_.flush(socket_);
  counters_.datagrams_out += r.sent;
  counters_.bytes_out += r.bytes_sent;
  counters_.send_failures += r.failed;
}

void Gateway::carryOut(Outbox& out) {
  for (const Reply& r : out.replies) {
    auto h = sessions_.findByToken(r.token);
    Session* s = h ? sessions_.get(*h) : nullptr;
    if (s != nullptr)
      sendTo(*s, r.bytes);
    else
      sendTo(r.to, r.bytes);
  }
  for (const SpawnCommand& c : out.spawns) {
    link_.requestSpawn(c);
    ++counters_.spawn_requests;
    ++counters_.sessions_opened;
  }
  for (const InputCommand& c : out.inputs) {
    if (link_.sendInput(c))
      ++counters_.inputs_forwarded;
    else
      ++counters_.input_write_failures;
  }
  CellDelta delta;
  for (const Session& s : out.closed) {
    retirePlayer(s, delta);
    ++counters_.sessions_closed;
  }
  applyCellDelta(delta);
  out.clear();
}

void Gateway::tick(std::int64_t now_ns) {
  std::int64_t cpu_ns = threadCpuNs();
  for (const zonesim_dds_OwnershipEvent& e : link_.takeOwnership()) applyOwnership(e);
  link_.flushSpawns();
  counters_.dds_samples += link_.takeCells(cache_, clock_, now_ns);
  cache_.sweep(now_ns);
  expireSessions(now_ns);
  updateInterest(now_ns);
  sendViews(now_ns);
  flushSends();
  double ms = double(nowNs() - now_ns) * 1e-6, cpu_ms = double(threadCpuNs() - cpu_ns) * 1e-6;
  tick_window_.add(ms);
  tick_total_.add(ms);
  tick_cpu_window_.add(cpu_ms);
  tick_cpu_total_.add(cpu_ms);
  if (now_ns >= next_metrics_ns_) {
    if (load_report_) load_report_->publish(sessions_.size(), handler_.tokenGate()->admitted());
    writeMetrics(now_ns);
    tick_window_ = {};
    tick_cpu_window_ = {};
    next_metrics_ns_ += kSecondNs;
  }
}

void Gateway::applyOwnership(const zonesim_dds_OwnershipEvent& e) {
  auto h = sessions_.findByPlayer(e.player_id);
  Session* s = h ? sessions_.get(*h) : nullptr;
  if (s == nullptr) {
    // Another gateway's player, or a session that already ended.
    ++counters_.ownership_foreign;
    return;
  }
  if (s->avatar_id != 0 && s->avatar_id != e.avatar_id) return;
  // Events of successive owners come from different writers in any order: an older one must
  // not route inputs back to a zone the avatar already left (an avatar moves once per tick).
  if (s->avatar_id != 0 && e.tick < s->owner_tick) {
    ++counters_.ownership_stale;
    return;
  }
  s->avatar_id = e.avatar_id;
  s->zone = e.to_zone;
  s->owner_tick = e.tick;
  if (!s->welcomed) {
    s->welcomed = true;
    s->last_input_seq = std::max(s->last_input_seq, e.last_input_seq);
    sendTo(*s, handler_.welcomeFor(*s));
    ++counters_.welcomes;
    return;
  }
  if (e.from_zone < 0) return;  // a repeated creation notice: nothing moved
  // Numbered and resent until acknowledged, like a Spawn: a newer handoff supersedes it.
  s->handoff = PendingHandoff{{e.avatar_id, e.from_zone, e.to_zone, e.tick, e.last_input_seq}, 0};
  sendHandoff(*s, nowNs());
  ++s->traffic.handoffs;
  ++counters_.handoffs;
}

void Gateway::sendHandoff(Session& s, std::int64_t now_ns) {
  PendingHandoff& h = *s.handoff;
  h.info.seq = s.resend.nextSeq();
  h.sent_ns = now_ns;
  s.resend.sent(h.info.seq, {}, Carried::Update, now_ns);
  sendTo(s, encodeHandoff(s.token, h.info));
}

void Gateway::resendHandoff(Session& s, std::int64_t now_ns) {
  if (!s.handoff) return;
  if (s.resend.acknowledged(s.handoff->info.seq)) {
    s.handoff.reset();
    return;
  }
  if (now_ns - s.handoff->sent_ns < s.resend.rtoNs()) return;
  sendHandoff(s, now_ns);
  ++s.traffic.handoffs_resent;
  ++counters_.handoffs_resent;
}

void Gateway::expireSessions(std::int64_t now_ns) {
  std::vector<std::pair<SlotHandle, bool>> dead;
  sessions_.forEach([&](SlotHandle h, Session& s) {
    bool silent = now_ns - s.last_heard_ns > seconds(config_.session_timeout_s);
    bool unborn = !s.welcomed && now_ns - s.created_ns > seconds(config_.pending_timeout_s);
    if (silent || unborn) dead.emplace_back(h, true);
  });
  for (auto& [h, expired] : dead) closeSession(h, expired);
}

void Gateway::retirePlayer(const Session& s, CellDelta& delta) {
  finished_players_.push_back(
      {s.player_id, double(nowNs() - s.created_ns) * 1e-9, s.traffic, s.kind});
  interest_.remove(s.player_id, delta);
  link_.requestDespawn(s.player_id);
}

void Gateway::closeSession(SlotHandle h, bool expired) {
  Session* s = sessions_.get(h);
  if (s == nullptr) return;
  CellDelta delta;
  retirePlayer(*s, delta);
  sessions_.erase(h);
  applyCellDelta(delta);
  ++(expired ? counters_.sessions_expired : counters_.sessions_closed);
}

void Gateway::avatarPosition(const Session& s, double sim_now, double& x, double& z) const {
  const CachedEntity* e = s.avatar_id != 0 ? cache_.find(s.avatar_id) : nullptr;
  if (e == nullptr) {
    x = s.spawn_x;
    z = s.spawn_z;
    return;
  }
  dr::V3 now = predictedPosition(*e, sim_now);
  x = now.x;
  z = now.z;
}

double Gateway::avatarSpeed(const Session& s) const {
  const CachedEntity* e = s.avatar_id != 0 ? cache_.find(s.avatar_id) : nullptr;
  return e == nullptr ? 0.0 : std::hypot(double(e->state.vel.x), double(e->state.vel.z));
}

double Gateway::nimbusOf(const Session& s) const {
  const AuraNimbus& an = config_.scene.aura_nimbus;
  return grownNimbus(kindOf(s).nimbus, avatarSpeed(s), an.nimbus_per_speed, an.max_nimbus);
}

void Gateway::updateInterest(std::int64_t now_ns) {
  double sim_now = clock_.simNow(now_ns);
  const AuraNimbus& an = config_.scene.aura_nimbus;
  double widest_aura = std::max({an.npc, an.avatar, an.rigid_body, an.emitter});
  CellDelta delta;
  sessions_.forEach([&](SlotHandle, Session& s) {
    double x, z;
    avatarPosition(s, sim_now, x, z);
    // The cells of everything the player may be shown (keep radius), plus the distance it can
    // cover in lookahead_s, so that cells are read before anything in them comes into view.
    double speed = std::max(avatarSpeed(s), kindOf(s).speed);
    double reach = std::min(nimbusOf(s), widest_aura) * 1.1 + speed * config_.lookahead_s;
    interest_.update(s.player_id, x, z, delta, reach);
  });
  applyCellDelta(delta);
}

void Gateway::applyCellDelta(const CellDelta& delta) {
  // One player's release and another's acquire of a cell in the same pass cancel out.
  for (int cell : delta.removed) {
    if (interest_.refcount(cell) > 0 || !link_.subscribed(cell)) continue;
    link_.unsubscribeCell(cell);
    cache_.dropCell(cell);
  }
  for (int cell : delta.added)
    if (interest_.refcount(cell) > 0)
      link_.subscribeCell(cell, grid_.columnOfCell(cell), grid_.rowOfCell(cell));
}

void Gateway::sendViews(std::int64_t now_ns) {
  double sim_now = clock_.simNow(now_ns);
  // The bucket fills by the time that passed, not by the tick: a gateway that falls behind its
  // cadence (an overloaded machine) still hands each player its budget. At most a send's worth
  // of ticks at once, so the bound on every 1 s window holds as at the nominal cadence.
  double refill_ticks = last_views_ns_ > 0
                            ? std::clamp(double(now_ns - last_views_ns_) / double(tick_ns_), 0.0,
                                         double(budget_ticks_per_send_))
                            : 1.0;
  last_views_ns_ = now_ns;
  ++views_;
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
    at.aura = {an.npc, an.avatar, an.rigid_body, an.emitter};
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
  });
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

Gateway::Fit Gateway::fitting(const Session& s, const Fit& forced,
                              const std::vector<std::pair<std::uint64_t, bool>>& ranked,
                              double available) const {
  // Encodes exactly what sendView will send (seq is a fixed-width field, the batch tick the
  // newest of the set), so the size measured here is the size sent.
  auto take = [&](std::size_t k) {
    Fit f = forced;
    for (std::size_t i = 0; i < k; ++i)
      (ranked[i].second ? f.spawns : f.updates).push_back(ranked[i].first);
    std::sort(f.spawns.begin(), f.spawns.end());
    std::sort(f.updates.begin(), f.updates.end());
    return f;
  };
  auto bytes = [&](const std::vector<std::uint64_t>& ids, bool spawns) {
    if (ids.empty()) return std::size_t{0};
    std::vector<dr::WireEntity> states;
    std::uint64_t tick = clock_.tick();
    for (std::uint64_t id : ids) {
      states.push_back(wireEntity(*cache_.find(id)));
      tick = std::max(tick, states.back().tick);
    }
    return totalBytes(spawns ? encodeSpawnChunks(s.token, tick, codec_, states, sizingSeq())
                             : encodeStateChunks(s.token, tick, codec_, states, sizingSeq()));
  };
  auto size = [&](const Fit& f) { return bytes(f.spawns, true) + bytes(f.updates, false); };
  // Forced traffic goes as debt: what the rest adds to it must fit.
  double base = double(size(forced));
  return take(longestFittingPrefix(available > 0 ? ranked.size() : 0, [&](std::size_t k) {
    return double(size(take(k))) - base <= available;
  }));
}

std::size_t Gateway::despawnBytes(const Session& s, std::span<const std::uint64_t> ids) const {
  if (ids.empty()) return 0;
  return totalBytes(encodeDespawnChunks(s.token, clock_.tick(), ids, sizingSeq()));
}

std::size_t Gateway::fittingDespawns(const Session& s, const std::vector<std::uint64_t>& ids,
                                     double available) const {
  return longestFittingPrefix(ids.size(), [&](std::size_t k) {
    return double(despawnBytes(s, std::span(ids).first(k))) <= available;
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
    std::size_t fit = fittingDespawns(s, diff.despawns, std::max(tokens, 0.0));
    for (std::size_t i = fit; i < diff.despawns.size(); ++i) {
      s.view.holdDespawn(diff.despawns[i]);
      ++s.traffic.deferred;
      ++counters_.deferred;
    }
    diff.despawns.resize(fit);
    tokens -= double(despawnBytes(s, diff.despawns));
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
  Fit forced;
  std::vector<std::tuple<int, double, std::uint64_t, bool>> order;  // band, -priority, id, spawn
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
    // tick (a third of 20 kbit/s went on that): it waits at most ticksPerSend - 1 ticks.
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
  std::vector<std::pair<std::uint64_t, bool>> ranked;
  ranked.reserve(order.size());
  for (auto& [band, key, id, spawn] : order) ranked.emplace_back(id, spawn);
  Fit go = fitting(s, forced, ranked, available);
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
  diff.spawns = std::move(go.spawns);
  diff.updates = std::move(go.updates);
}

void Gateway::sendView(Session& s, const ViewDiff& diff, std::int64_t now_ns) {
  // States go out as the zones sampled them, with their tick: the client runs the same model
  // from the same state, so nothing is extrapolated here.
  auto states = [&](const std::vector<std::uint64_t>& ids) {
    std::vector<dr::WireEntity> out;
    out.reserve(ids.size());
    for (std::uint64_t id : ids) out.push_back(wireEntity(*cache_.find(id)));
    return out;
  };
  std::uint64_t tick = clock_.tick();
  auto newest = [&](const std::vector<dr::WireEntity>& v) {
    std::uint64_t t = tick;
    for (const dr::WireEntity& e : v) t = std::max(t, e.tick);
    return t;
  };
  // Every datagram gets the session's next seq (consecutive within one encoding); the tracker
  // learns which ids each one held.
  std::vector<std::size_t> counts;
  ChunkSeq seq{[](void* t) { return static_cast<ResendTracker*>(t)->nextSeq(); }, &s.resend,
               &counts};
  auto send = [&](std::uint32_t first, const std::vector<Bytes>& chunks,
                  const std::vector<std::uint64_t>& ids, Carried what) {
    std::size_t at = 0;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
      sendTo(s, chunks[i]);
      if (config_.resend)
        s.resend.sent(first + std::uint32_t(i), std::span(ids).subspan(at, counts[i]), what,
                      now_ns);
      at += counts[i];
    }
    counts.clear();
  };
  std::vector<dr::WireEntity> spawns = states(diff.spawns), updates = states(diff.updates);
  std::uint32_t first = s.resend.upcoming();
  send(first, encodeDespawnChunks(s.token, tick, diff.despawns, seq), diff.despawns,
       Carried::Despawn);
  first = s.resend.upcoming();
  send(first, encodeSpawnChunks(s.token, newest(spawns), codec_, spawns, seq), diff.spawns,
       Carried::Spawn);
  first = s.resend.upcoming();
  send(first, encodeStateChunks(s.token, newest(updates), codec_, updates, seq), diff.updates,
       Carried::Update);
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

void Gateway::sendTo(Session& s, const Bytes& bytes) {
  ++s.traffic.datagrams_out;
  s.traffic.bytes_out += bytes.size();
  if (config_.budget.enabled()) s.budget.spend(bytes.size());
  sendTo(s.address, bytes);
}

void Gateway::sendTo(const Endpoint& to, const Bytes& bytes) {
  // Unimpaired, datagrams wait for one sendmmsg at the end of the tick (or of the wake).
  if (!impairment_.active()) {
    send_queue_.push(to, bytes);
    return;
  }
  if (!impairment_.send(socket_, to, bytes, nowNs())) {
    ++counters_.send_failures;
    return;
  }
  ++counters_.datagrams_out;
  counters_.bytes_out += bytes.size();
}

double Gateway::processCpuMsPerTick() const {
  return tick_total_.count > 0
             ? double(processCpuNs() - start_process_cpu_ns_) * 1e-6 / double(tick_total_.count)
             : 0.0;
}

GatewayGauges Gateway::gauges(std::int64_t now_ns) {
  GatewayGauges g;
  g.elapsed_s = double(now_ns - start_ns_) * 1e-9;
  g.sessions = sessions_.size();
  sessions_.forEach([&](SlotHandle, Session& s) { g.pending_sessions += s.welcomed ? 0 : 1; });
  g.cells_subscribed = link_.subscribedCells();
  g.entities_cached = cache_.size();
  g.held_spawns = link_.heldSpawns();
  g.zone_tick = clock_.tick();
  g.tick_ms = tick_window_;
  g.tick_cpu_ms = tick_cpu_window_;
  g.process_cpu_ms_per_tick = processCpuMsPerTick();
  return g;
}

void Gateway::writeMetrics(std::int64_t now_ns) {
  GatewayGauges g = gauges(now_ns);
  // Each client's bytes over the second just ended; the worst is kept for the summary, with
  // or without a metrics file.
  std::vector<double>& kbps = kbps_scratch_;
  kbps.clear();
  sessions_.forEach([&](SlotHandle, Session& s) {
    kbps.push_back(double(s.traffic.bytes_out - s.bytes_out_at_second) * 8.0 / 1000.0);
    s.bytes_out_at_second = s.traffic.bytes_out;
  });
  if (!kbps.empty()) {
    std::sort(kbps.begin(), kbps.end());
    g.client_kbps_p50 = kbps[kbps.size() / 2];
    g.client_kbps_max = kbps.back();
    worst_client_kbps_ = std::max(worst_client_kbps_, g.client_kbps_max);
  }
  if (metrics_.enabled()) metrics_.write(metricsLine(counters_, handler_.drops(), g));
}

std::string Gateway::summaryJson() {
  std::int64_t now = nowNs();
  std::vector<PlayerRecord> players = finished_players_;
  sessions_.forEach([&](SlotHandle, Session& s) {
    players.push_back({s.player_id, double(now - s.created_ns) * 1e-9, s.traffic, s.kind});
  });
  std::sort(players.begin(), players.end(),
            [](const auto& a, const auto& b) { return a.player_id < b.player_id; });
  GatewayGauges g = gauges(now);
  g.tick_ms = tick_total_;
  g.tick_cpu_ms = tick_cpu_total_;
  // Over the run: the median player's mean rate, and the worst second of any player.
  std::vector<double> kbps;
  for (const PlayerRecord& p : players)
    if (p.seconds > 0) kbps.push_back(double(p.traffic.bytes_out) * 8.0 / 1000.0 / p.seconds);
  std::sort(kbps.begin(), kbps.end());
  g.client_kbps_p50 = kbps.empty() ? 0.0 : kbps[kbps.size() / 2];
  g.client_kbps_max = worst_client_kbps_;
  return gateway::summaryJson(counters_, handler_.drops(), g, players);
}

}  // namespace zonesim::gateway
