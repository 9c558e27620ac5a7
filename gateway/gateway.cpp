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
#include "common/stats.h"
#include "common/timer.h"

namespace zonesim::gateway {

namespace {
constexpr std::int64_t kSecondNs = 1'000'000'000;
// Bounded so a flood of datagrams cannot starve the tick.
constexpr int kMaxDatagramsPerWake = 4096;

std::int64_t seconds(double s) {
  return std::int64_t(s * 1e9);
}

HandlerConfig handlerConfig(const GatewayConfig& c) {
  HandlerConfig h{c.scene.world, float(c.scene.tick_rate), c.spawn_seed, dr::codecParams(c.scene),
                  float(c.scene.dt)};
  h.auth_key = c.auth_key;
  h.resume_key = c.resume_key;
  h.gateway_id = std::uint16_t(c.gateway_id);
  h.kinds = 0;
  for (const PlayerKind& k : playerKinds(c.scene.clients)) h.kinds |= std::uint32_t{1} << int(k.id);
  return h;
}

/// A random non-zero 15-bit number per gateway process: player ids of a restarted gateway (and
/// of gateways left at the same --gateway-id) differ from the ones the zones already saw. Not
/// 16 bits: ids stay below 2^63, the largest key the ledger's databases store (signed 64-bit).
std::uint16_t randomIncarnation() {
  std::random_device rd;
  return std::uint16_t(1 + rd() % 0x7FFF);
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
      timeline_(config_.scene.dt),
      interest_(grid_, interestRadius(config_), grid_.cell_size() * 0.5),
      kinds_(kindTable(config_.scene)),
      link_(config_.dds_domain, expectedZones(config_)),
      rx_batch_(kMaxDatagramBytes + 1),
      codec_(dr::codecParams(config_.scene)),
      impairment_(config_.impairment, 0x9a7e) {
  if (!config_.metrics_path.empty()) metrics_ = MetricsWriter(config_.metrics_path);
  if (!config_.record_dir.empty())
    recorder_ = std::make_unique<GatewayRecorder>(config_.record_dir, int(config_.gateway_id),
                                                  config_.scene, grid_, codec_);
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
  if (config_.record_every_ticks < 1)
    throw std::invalid_argument("gateway: --record-every-ticks must be at least 1, not " +
                                std::to_string(config_.record_every_ticks));
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
    counters_.sessions_resumed += c.resumed ? 1 : 0;
  }
  for (const InputCommand& c : out.inputs) {
    if (link_.sendInput(c))
      ++counters_.inputs_forwarded;
    else
      ++counters_.input_write_failures;
  }
  counters_.inputs_recovered = handler_.inputsRecovered();
  for (const LeaderboardCommand& c : out.leaderboards) {
    if (link_.askLeaderboard(c))
      ++counters_.leaderboard_queries;
    else
      ++counters_.leaderboard_write_failures;
  }
  for (const TransactionCommand& c : out.transactions) {
    if (link_.sendTransaction(c))
      ++counters_.transactions_forwarded;
    else
      ++counters_.transaction_write_failures;
  }
  CellDelta delta;
  for (const Session& s : out.closed) {
    retirePlayer(s, delta);
    ++counters_.sessions_closed;
  }
  for (const Session& s : out.replaced) {
    releasePlayer(s, delta);
    ++counters_.sessions_replaced;
  }
  applyCellDelta(delta);
  out.clear();
}

void Gateway::tick(std::int64_t now_ns) {
  std::int64_t cpu_ns = threadCpuNs();
  for (const zonesim_dds_OwnershipEvent& e : link_.takeOwnership()) applyOwnership(e);
  deliverOutcomes();
  link_.flushSpawns();
  counters_.dds_samples += link_.takeCells(cache_, clock_, timeline_, now_ns);
  followEpochs(now_ns);
  resendInputs(now_ns);
  handler_.setDilation(clock_.dilation());
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

Session* Gateway::welcomedSessionOf(std::uint64_t player_id) {
  auto h = sessions_.findByPlayer(player_id);
  Session* s = h ? sessions_.get(*h) : nullptr;
  return s != nullptr && s->welcomed ? s : nullptr;
}

void Gateway::deliverOutcomes() {
  for (const TransactionOutcomeMsg& o : link_.takeOutcomes()) {
    Session* s = welcomedSessionOf(o.player_id);
    if (s == nullptr) {
      // Another gateway's player, or one gone: it sends the transaction again wherever it
      // plays now, and its zone answers again.
      ++counters_.outcomes_foreign;
      continue;
    }
    sendTo(*s, encodeTransactionOutcome(s->token, o.seq, o.status, o.reason));
    ++counters_.outcomes_delivered;
  }
  for (const LeaderboardReplyMsg& r : link_.takeLeaderboards()) {
    Session* s = welcomedSessionOf(r.player_id);
    if (s == nullptr) continue;  // another gateway's player, or one gone
    sendTo(*s, encodeLeaderboard(s->token, r.rows, r.reason));
    ++counters_.leaderboards_delivered;
  }
}

void Gateway::applyOwnership(const zonesim_dds_OwnershipEvent& e) {
  std::optional<std::uint64_t> tick = timeline_.mapTick(e.epoch, e.tick);
  if (!tick) return;  // from a zone of a world since restarted (counted by the timeline)
  auto h = sessions_.findByPlayer(e.player_id);
  Session* s = h ? sessions_.get(*h) : nullptr;
  if (s == nullptr) {
    // Another gateway's player, or a session that already ended.
    ++counters_.ownership_foreign;
    return;
  }
  // A restored world may own the avatar elsewhere, or, asked anew, under a new id.
  bool restored = s->welcomed && e.epoch > s->owner_epoch;
  if (s->avatar_id != 0 && s->avatar_id != e.avatar_id && !restored && !s->respawning) return;
  // Events of successive owners come from different writers in any order: an older one must
  // not route inputs back to a zone the avatar already left (an avatar moves once per tick).
  if (s->avatar_id != 0 && *tick < s->owner_tick) {
    ++counters_.ownership_stale;
    return;
  }
  bool avatar_changed = s->avatar_id != 0 && s->avatar_id != e.avatar_id;
  bool zone_changed = s->zone != e.to_zone;
  s->avatar_id = e.avatar_id;
  s->zone = e.to_zone;
  s->owner_tick = *tick;
  s->owner_epoch = e.epoch;
  if (restored || s->respawning) {
    adoptRestoredOwner(*s, e, *tick, avatar_changed, zone_changed);
    return;
  }
  if (!s->welcomed) {
    s->welcomed = true;
    s->last_input_seq = std::max(s->last_input_seq, e.last_input_seq);
    sendTo(*s, handler_.welcomeFor(*s));
    ++counters_.welcomes;
    return;
  }
  if (e.from_zone < 0) return;  // a repeated creation notice: nothing moved
  // Numbered and resent until acknowledged, like a Spawn: a newer handoff supersedes it.
  s->handoff = PendingHandoff{{e.avatar_id, e.from_zone, e.to_zone, *tick, e.last_input_seq}, 0};
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

void Gateway::releasePlayer(const Session& s, CellDelta& delta) {
  finished_players_.push_back(
      {s.player_id, double(nowNs() - s.created_ns) * 1e-9, s.traffic, s.kind});
  interest_.remove(s.player_id, delta);
}

void Gateway::retirePlayer(const Session& s, CellDelta& delta) {
  releasePlayer(s, delta);
  link_.requestDespawn(s.player_id, s.session_id);
}

void Gateway::closeSession(SlotHandle h, bool expired) {
  Session* s = sessions_.get(h);
  if (s == nullptr) return;
  CellDelta delta;
  // A resume that was never welcomed here leaves the avatar alone: the player may have been
  // taken back by another gateway it also asked, or its avatar was already gone. The zone's
  // orphan grace removes one nobody plays.
  if (s->resumed && !s->welcomed)
    releasePlayer(*s, delta);
  else
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

void Gateway::sendTo(Session& s, const Bytes& bytes) {
  ++s.traffic.datagrams_out;
  s.traffic.bytes_out += bytes.size();
  if (recorder_ && !isDownlinkFrame(bytes)) recorder_->controlDatagram(s.player_id, bytes.size());
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
  g.epoch = timeline_.epoch();
  g.zone_dilation = clock_.dilation();
  g.zone_dilation_min = clock_.minDilation();
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
  if (recorder_) g.record_frames_mismatched = recorder_->framesMismatched();
  const std::vector<float>& jumps = cache_.epochJumps();
  if (!jumps.empty()) {
    std::vector<double> m(jumps.begin(), jumps.end());
    g.epoch_jumps = m.size();
    g.epoch_jump_m_p50 = percentile(m, 50);
    g.epoch_jump_m_p99 = percentile(m, 99);
    g.epoch_jump_m_max = percentile(m, 100);
  }
  return gateway::summaryJson(counters_, handler_.drops(), g, players);
}

}  // namespace zonesim::gateway
