#include "clients/sim_player.h"

#include <algorithm>
#include <cmath>

#include "common/splitmix.h"
#include "common/timer.h"
#include "dr/truth_sample.h"

namespace zonesim::clients {

namespace {
std::int64_t seconds(double s) {
  return std::int64_t(s * 1e9);
}
// A resuming player asks often: a restarted gateway is up within a second.
constexpr double kResumeHelloRetryS = 0.2;
// And asks one gateway this long before the next: a resumed Welcome takes a zone's answer.
constexpr double kResumeStayS = 1.0;
// Silent for half of resume_after_s, the player pings this often: a live gateway whose zones
// are restarting (no states, no clock) answers, and the player does not leave it.
constexpr double kProbeEveryS = 0.1;
// An hour of own states at 30 Hz: the log stays bounded whatever the run length.
constexpr std::size_t kMaxOwnEvents = 108'000;
// Sampled entities shown, per player (32 bytes each): minutes of a view with a dozen sampled.
constexpr std::size_t kMaxDisplaySamples = 100'000;
}  // namespace

SimPlayer::SimPlayer(const PlayerConfig& config, std::uint32_t index, std::int64_t start_ns)
    : SimPlayer(config, index, start_ns, gateway::UdpSocket(gateway::Endpoint::any(0))) {}

SimPlayer::SimPlayer(const PlayerConfig& config, std::uint32_t index, std::int64_t start_ns,
                     gateway::UdpSocket socket)
    : config_(config),
      socket_(std::move(socket)),
      // Nonces only match replies to requests; mixing in the port keeps two runs apart.
      nonce_(splitmix64(config.seed ^ (std::uint64_t{index} << 32)) ^
             std::uint64_t(socket_.localPort())),
      transactions_(config.transactions_per_s, splitmix64(config.seed ^ 0x7a ^ index), start_ns),
      start_ns_(start_ns),
      next_hello_ns_(start_ns),
      next_input_ns_(INT64_MAX),
      next_ping_ns_(INT64_MAX),
      input_period_ns_(std::max<std::int64_t>(1, seconds(1.0 / config.input_hz))),
      wander_(config.world, config.retarget_seconds, config.seed, index, config.kind.speed),
      impairment_(config.impairment, index),
      rx_buffer_(gateway::kMaxDatagramBytes + 1) {
  if (nonce_ == 0) nonce_ = 1;
}

double SimPlayer::welcomeSeconds() const {
  if (welcome_ns_ < 0 || first_hello_ns_ < 0) return -1;
  return double(welcome_ns_ - first_hello_ns_) * 1e-9;
}

void SimPlayer::send(const gateway::Bytes& bytes) {
  bool ok = impairment_.active() ? impairment_.send(socket_, gateway(), bytes, nowNs())
                                 : socket_.sendTo(gateway(), bytes);
  if (!ok) {
    ++counters_.send_failures;
    return;
  }
  ++counters_.datagrams_out;
  counters_.bytes_out += bytes.size();
}

std::int64_t SimPlayer::act(std::int64_t now_ns) {
  if (impairment_.active()) {
    deliverHeld(now_ns);
    counters_.send_failures += impairment_.flush(socket_, now_ns);
  }
  std::int64_t due = actDue(now_ns);
  // After actDue: what it just sent may be held on the uplink, and must go out when due, not
  // at the next input.
  due = std::min(due, impairment_.nextDueNs());
  return config_.truth_every > 0 ? std::min(due, logDisplay(now_ns)) : due;
}

std::int64_t SimPlayer::logDisplay(std::int64_t now_ns) {
  if (!welcomed() || clock_tick_ < 0) return INT64_MAX;  // no server clock yet
  double now_tick = serverTick(now_ns);
  auto tick = std::int64_t(now_tick);
  if (tick > displayed_tick_ && displayed_.size() < kMaxDisplaySamples) {
    displayed_tick_ = tick;
    // Distances are from where the player draws itself: the band an error falls in.
    auto self = avatar_id_ != 0 ? view_.shown(avatar_id_, double(tick)) : std::nullopt;
    view_.forEach([&](std::uint64_t id, const dr::WireEntity& e) {
      if (!dr::truthSampled(id, config_.truth_every)) return;
      // What the player would draw for that tick, with what it knows now.
      auto p = view_.shown(id, double(tick));
      if (!p) return;
      float distance = self ? float(std::hypot(p->x - self->x, p->z - self->z)) : -1.0f;
      displayed_.push_back({std::uint64_t(tick), id, e.model.order, float(p->x), float(p->y),
                            float(p->z), distance});
    });
  }
  return now_ns + std::int64_t((double(tick + 1) - now_tick) / ticksPerSecond() * 1e9) + 1;
}

std::int64_t SimPlayer::helloDue(std::int64_t now_ns) {
  if (resuming_ && now_ns - resume_started_ns_ > seconds(config_.resume_give_up_s)) {
    // No gateway took the player back: it comes as a new one (the lobby's token, if any,
    // was for its first gateway: a gateway with a key refuses it, and the count says so).
    ++counters_.resume_failed;
    resuming_ = false;
    resume_token_.clear();
    player_id_ = avatar_id_ = 0;
    seq_ = 0;  // a new avatar's inputs start at 1
    sent_inputs_ = gateway::InputHistory();
    transactions_.restart(now_ns);
    startNewStream();
  }
  if (now_ns >= next_hello_ns_) {
    if (resuming_ && now_ns - resume_gateway_since_ns_ >= seconds(kResumeStayS)) {
      gateway_index_ = (gateway_index_ + 1) % (1 + config_.fallback_gateways.size());
      resume_gateway_since_ns_ = now_ns;
    }
    send(gateway::encodeHello(nonce_, "player", config_.connect_token,
                              std::uint8_t(config_.kind.id),
                              resuming_ ? std::span(resume_token_)
                                        : std::span<const std::uint8_t>()));
    ++counters_.hellos;
    if (first_hello_ns_ < 0) first_hello_ns_ = now_ns;
    next_hello_ns_ = now_ns + seconds(resuming_ ? kResumeHelloRetryS : config_.hello_retry_s);
  }
  return next_hello_ns_;
}

std::int64_t SimPlayer::actDue(std::int64_t now_ns) {
  if (!welcomed()) return helloDue(now_ns);
  if (config_.resume_after_s > 0 && !resume_token_.empty() &&
      now_ns - last_heard_ns_ > seconds(config_.resume_after_s)) {
    beginResume(now_ns);
    return now_ns;
  }
  if (now_ns >= next_input_ns_) {
    sendInput(now_ns);
    next_input_ns_ += input_period_ns_;
    if (next_input_ns_ <= now_ns) next_input_ns_ = now_ns + input_period_ns_;
  }
  bool probing = config_.resume_after_s > 0 && !resume_token_.empty() &&
                 now_ns - last_heard_ns_ > seconds(config_.resume_after_s / 2);
  if (probing) next_ping_ns_ = std::min(next_ping_ns_, last_ping_ns_ + seconds(kProbeEveryS));
  if (now_ns >= next_ping_ns_) {
    send(gateway::encodePing(token_, std::uint64_t(now_ns / 1000), acks_.ack(), acks_.bits()));
    last_ping_ns_ = now_ns;
    next_ping_ns_ = now_ns + seconds(probing ? kProbeEveryS : config_.ping_every_s);
  }
  std::int64_t due = std::min(next_input_ns_, next_ping_ns_);
  if (config_.leaderboard_every_s > 0) {
    if (next_leaderboard_ns_ == INT64_MAX)
      next_leaderboard_ns_ = now_ns + seconds(config_.leaderboard_every_s);
    if (now_ns >= next_leaderboard_ns_) {
      send(gateway::encodeLeaderboardQuery(token_, std::uint8_t(gateway::kMaxLeaderboardRows)));
      ++counters_.leaderboard_queries;
      next_leaderboard_ns_ = now_ns + seconds(config_.leaderboard_every_s);
    }
    due = std::min(due, next_leaderboard_ns_);
  }
  due = std::min(due, transactions_.due(now_ns, [&](const gateway::TransactionInfo& t) {
    send(gateway::encodeTransaction(token_, t));
  }));
  if (config_.resume_after_s > 0 && !resume_token_.empty()) {
    std::int64_t probe_at = last_heard_ns_ + seconds(config_.resume_after_s / 2) + 1;
    std::int64_t resume_at = last_heard_ns_ + seconds(config_.resume_after_s) + 1;
    due = std::min(due, probing ? resume_at : probe_at);
  }
  return due;
}

const Endpoint& SimPlayer::knownGateway(std::size_t index) const {
  return index == 0 ? config_.gateway : config_.fallback_gateways[index - 1];
}

bool SimPlayer::isKnownGateway(const Endpoint& e) const {
  return e == config_.gateway || std::find(config_.fallback_gateways.begin(),
                                           config_.fallback_gateways.end(),
                                           e) != config_.fallback_gateways.end();
}

void SimPlayer::startNewStream() {
  view_ = RemoteView();
  lifecycle_.clear();
  unknown_.clear();
  acks_ = gateway::AckWindow();
  clock_tick_ = newest_tick_ = -1;
  handoffs_seen_ = 0;
  last_handoff_tick_ = 0;
  displayed_tick_ = -1;
}

void SimPlayer::beginResume(std::int64_t now_ns) {
  token_ = 0;
  resuming_ = true;
  resume_started_ns_ = now_ns;
  next_hello_ns_ = now_ns;
  // A new nonce: a late Welcome of the old session is not this one's. The first Hellos go
  // to the same gateway (restarted on its address), later ones to the next one known.
  nonce_ = splitmix64(nonce_) | 1;
  resume_gateway_since_ns_ = now_ns;
}

void SimPlayer::setDilation(float factor, std::int64_t now_ns) {
  // The Verifier checks structure only: a factor no gateway sends is dropped, the clock kept.
  if (!(factor > 0.0f && factor <= 1.0f)) {
    counters_.drops.add(gateway::DropReason::OutOfRange);
    return;
  }
  if (double(factor) == dilation_) return;
  // Re-anchor where the clock is now, so that only its rate changes from here on.
  if (clock_tick_ >= 0) {
    clock_tick_ = serverTick(now_ns);
    clock_ns_ = now_ns;
  }
  dilation_ = double(factor);
  counters_.min_dilation = std::min(counters_.min_dilation, dilation_);
}

double SimPlayer::serverTick(std::int64_t now_ns) const {
  if (clock_tick_ < 0) return 0;
  double run_on = clock_tick_ + double(now_ns - clock_ns_) * 1e-9 * ticksPerSecond();
  if (config_.max_lead_s <= 0) return run_on;
  return std::min(run_on, newest_tick_ + config_.max_lead_s * ticksPerSecond());
}

std::optional<std::vector<dr::WireEntity>> SimPlayer::unpack(const gateway::DownlinkFrame& f,
                                                             std::int64_t now_ns) {
  std::uint64_t server_tick = f.header.tick;
  auto got = codec_->unpack(f.payload, f.header.count, server_tick);
  if (!got) {
    counters_.drops.add(gateway::DropReason::OutOfRange);
    return got;
  }
  // Follow the server clock: jump forward to a newer tick; fall back only when the estimate
  // ran more than a second ahead (the gateway stalled or the rate was off).
  double est = serverTick(now_ns);
  newest_tick_ = std::max(newest_tick_, double(server_tick));
  if (clock_tick_ < 0 || double(server_tick) > est || est - double(server_tick) > tick_rate_) {
    clock_tick_ = double(server_tick);
    clock_ns_ = now_ns;
  }
  return got;
}

void SimPlayer::logOwn(std::int64_t now_ns, std::uint64_t tick, bool handoff) {
  if (own_.size() < kMaxOwnEvents) own_.push_back({now_ns, tick, serverTick(now_ns), handoff});
}

void SimPlayer::sendInput(std::int64_t now_ns) {
  Move m;
  // Until the avatar's own state arrives the player does not know where it is: stand still.
  if (auto self = view_.predicted(avatar_id_, serverTick(now_ns)))
    m = wander_.step(self->x, self->z, double(now_ns - start_ns_) * 1e-9);
  // The last few again, so that one lost datagram costs the zone no input.
  earlier_.clear();
  const std::uint32_t r = config_.input_redundancy;
  if (r > 0)
    sent_inputs_.since(seq_ + 1 > r ? seq_ + 1 - r : 1,
                       [&](const gateway::InputRecord& in) { earlier_.push_back(in); });
  send(gateway::encodeInput(token_, ++seq_, m.x, m.z, acks_.ack(), acks_.bits(), earlier_));
  sent_inputs_.record({seq_, m.x, m.z});
  ++counters_.inputs;
  visible_sum_ += double(view_.size());
  ++visible_samples_;
}

void SimPlayer::bye() {
  if (welcomed()) send(gateway::encodeBye(token_));
}

std::int64_t SimPlayer::flushUplink(std::int64_t now_ns) {
  if (!impairment_.active()) return INT64_MAX;
  counters_.send_failures += impairment_.flush(socket_, now_ns);
  return impairment_.nextOutgoingDueNs();
}

void SimPlayer::receive(std::int64_t now_ns) {
  while (auto got = socket_.receive(rx_buffer_))
    take(std::span(rx_buffer_.data(), std::min(got->size, rx_buffer_.size())), *got, now_ns);
}

void SimPlayer::receive(std::int64_t now_ns, gateway::ReceiveBatch& batch) {
  for (;;) {
    std::size_t n = batch.receive(socket_);
    for (std::size_t i = 0; i < n; ++i) take(batch.bytes(i), batch.received(i), now_ns);
    if (n < gateway::ReceiveBatch::kBatch) return;  // short: the socket was empty when read
  }
}

void SimPlayer::take(std::span<const std::uint8_t> bytes, const gateway::Received& got,
                     std::int64_t now_ns) {
  ++counters_.datagrams_in;
  counters_.bytes_in += got.size;
  if (got.truncated || got.size > gateway::kMaxDatagramBytes) {
    counters_.drops.add(gateway::DropReason::TooLarge);
    return;
  }
  if (impairment_.active())
    impairment_.receive(bytes, got.from, now_ns);  // the downlink: lost, or held a while
  else
    handle(bytes, got.from, now_ns);
}

void SimPlayer::deliverHeld(std::int64_t now_ns) {
  impairment_.deliver(now_ns, [&](std::span<const std::uint8_t> bytes, const Endpoint& from) {
    handle(bytes, from, now_ns);
  });
}

void SimPlayer::handle(std::span<const std::uint8_t> bytes, const Endpoint& from,
                       std::int64_t now_ns) {
  using gateway::DropReason;
  if (from != gateway()) {
    // A resuming player asked several gateways in turn: whichever welcomes it first is the
    // one it plays through (a Hello to another may still be answered).
    if (!resuming_ || !isKnownGateway(from)) {
      counters_.drops.add(DropReason::WrongAddress);
      return;
    }
  }
  if (gateway::isDownlinkFrame(bytes)) {
    // Checked against our token (none before the Welcome: not_ready).
    gateway::ParsedFrame f = gateway::parseFrame(bytes, token_);
    if (!f.ok()) {
      counters_.drops.add(*f.drop);
      return;
    }
    last_heard_ns_ = now_ns;
    onFrame(f.frame, now_ns);
    return;
  }
  gateway::Verified v = gateway::verifyDatagram(bytes, gateway::Direction::ToClient);
  if (!v.ok()) {
    counters_.drops.add(v.reason);
    return;
  }
  const proto::Datagram& d = *v.datagram;
  if (d.msg_type() == proto::Message::Welcome) {
    bool was_welcomed = welcomed();
    onWelcome(d, now_ns);
    if (!was_welcomed && welcomed()) {
      for (std::size_t i = 0; i <= config_.fallback_gateways.size(); ++i)
        if (knownGateway(i) == from) gateway_index_ = i;
    }
    return;
  }
  if (welcomed() && d.token() == token_) last_heard_ns_ = now_ns;
  if (!welcomed()) {
    counters_.drops.add(DropReason::NotReady);
    return;
  }
  if (d.token() != token_) {
    counters_.drops.add(DropReason::BadToken);
    return;
  }
  onMessage(d, now_ns);
}

void SimPlayer::onWelcome(const proto::Datagram& d, std::int64_t now_ns) {
  const proto::Welcome* w = d.msg_as_Welcome();
  // The Welcome must answer our Hello and carry the token it announces.
  if (w->client_nonce() != nonce_ || d.token() != w->token()) {
    counters_.drops.add(gateway::DropReason::BadToken);
    return;
  }
  if (welcomed()) return;  // a re-sent Welcome for our own retry
  token_ = w->token();
  if (const flatbuffers::Vector<std::uint8_t>* r = w->resume_token())
    resume_token_.assign(r->begin(), r->end());
  else
    resume_token_.clear();
  if (resuming_) {
    onResumed(*w, now_ns);
  } else {
    player_id_ = w->player_id();
    welcome_ns_ = now_ns;
  }
  avatar_id_ = w->avatar_id();
  zone_ = w->zone();
  codec_.emplace(gateway::fromProto(*w->codec()));
  tick_rate_ = w->tick_rate();
  view_.configure({config_.blend, config_.blend_s, double(w->sim_dt())});
  last_heard_ns_ = now_ns;
  next_input_ns_ = now_ns;
  next_ping_ns_ = now_ns;
}

void SimPlayer::onResumed(const proto::Welcome& w, std::int64_t now_ns) {
  resuming_ = false;
  ++counters_.resumes;
  counters_.resume_s.add(double(now_ns - last_heard_ns_) * 1e-9);
  if (w.avatar_id() != avatar_id_) ++counters_.resume_new_avatar;
  startNewStream();
  // The old session's outcomes may be lost with its gateway: ask again at once.
  transactions_.onNewSession();
  // What the zone did not apply (sent to the dead gateway, or lost with it) goes again, in
  // order, before anything new: the zone applies each seq once.
  std::uint32_t applied = w.last_input_seq();
  if (seq_ > applied) {
    counters_.inputs_unresendable += sent_inputs_.since(applied + 1, [&](const gateway::InputRecord& in) {
      send(gateway::encodeInput(token_, in.seq, in.move_x, in.move_z));
      ++counters_.inputs_resent;
    });
  }
}

bool SimPlayer::fresh(std::uint32_t seq) {
  if (seq == 0) return true;  // an unnumbered datagram (an older gateway): no acks, no dedup
  if (acks_.receive(seq)) return true;
  ++counters_.duplicates;
  return false;
}

bool SimPlayer::newerLifecycle(std::uint64_t id, std::uint32_t seq) {
  auto [it, inserted] = lifecycle_.try_emplace(id, seq);
  if (inserted) return true;
  if (seq != 0 && seq < it->second) {
    ++counters_.stale_lifecycle;
    return false;
  }
  it->second = seq;
  return true;
}

std::size_t SimPlayer::ghosts(std::int64_t now_ns) const {
  double limit = serverTick(now_ns) - config_.stale_after_s * ticksPerSecond();
  std::size_t n = 0;
  view_.forEach([&](std::uint64_t id, const dr::WireEntity& e) {
    if (id != avatar_id_ && double(e.tick) < limit) ++n;
  });
  return n;
}

std::size_t SimPlayer::unspawned() const {
  std::size_t n = 0;
  for (const auto& [id, u] : unknown_) n += u.last_ns - u.first_ns > 1'000'000'000 ? 1 : 0;
  return n;
}

void SimPlayer::onFrame(const gateway::DownlinkFrame& f, std::int64_t now_ns) {
  if (!fresh(f.header.seq)) return;
  switch (f.header.kind) {
    case gateway::FrameKind::Spawn:
      onSpawn(f, now_ns);
      return;
    case gateway::FrameKind::StateBatch:
      onStates(f, now_ns);
      return;
    case gateway::FrameKind::Despawn:
      onDespawn(f);
      return;
  }
}

void SimPlayer::onSpawn(const gateway::DownlinkFrame& f, std::int64_t now_ns) {
  auto got = unpack(f, now_ns);
  if (!got) return;
  for (const dr::WireEntity& e : *got) {
    if (!newerLifecycle(e.id, f.header.seq)) continue;
    unknown_.erase(e.id);
    // A resent spawn of an entity already shown is its newest state: blend, do not jump.
    const dr::WireEntity* held = view_.find(e.id);
    bool newer = held == nullptr || e.tick > held->tick;
    counters_.repeats += newer ? 0 : 1;
    if (held != nullptr)
      view_.update(e, serverTick(now_ns));
    else
      view_.spawn(e, serverTick(now_ns));
    if (e.id == avatar_id_ && newer) logOwn(now_ns, e.tick, false);
    ++counters_.spawns;
  }
}

void SimPlayer::onStates(const gateway::DownlinkFrame& f, std::int64_t now_ns) {
  auto got = unpack(f, now_ns);
  if (!got) return;
  for (const dr::WireEntity& e : *got) {
    if (auto err = view_.update(e, serverTick(now_ns))) {
      counters_.dr_error_m.add(*err);
      if (e.id == avatar_id_) logOwn(now_ns, e.tick, false);
    } else if (view_.find(e.id) != nullptr) {
      ++counters_.repeats;  // already held: a resend whose first copy arrived
    } else {
      // Updated after its last despawn here: the gateway thinks we know it.
      auto l = lifecycle_.find(e.id);
      if (l == lifecycle_.end() || l->second < f.header.seq) {
        auto [u, _] = unknown_.try_emplace(e.id, Unknown{now_ns, now_ns});
        u->second.last_ns = now_ns;
      }
    }
    ++counters_.updates;
  }
}

void SimPlayer::onDespawn(const gateway::DownlinkFrame& f) {
  for (std::uint64_t id : f.ids) {
    if (!newerLifecycle(id, f.header.seq)) continue;
    unknown_.erase(id);
    counters_.despawns += view_.despawn(id);
  }
}

void SimPlayer::onMessage(const proto::Datagram& d, std::int64_t now_ns) {
  switch (d.msg_type()) {
    case proto::Message::Handoff: {
      // Resent under a new seq until acknowledged: the crossing tick tells a repeat (or a
      // notice overtaken by a newer handoff) from news.
      const proto::Handoff* h = d.msg_as_Handoff();
      if (!fresh(h->seq())) return;
      if (handoffs_seen_ > 0 && h->tick() <= last_handoff_tick_) {
        ++counters_.repeats;
        return;
      }
      ++handoffs_seen_;
      last_handoff_tick_ = h->tick();
      zone_ = h->to_zone();
      // A zone restarted without our avatar made a new one (gateway/gateway_epochs.cpp).
      if (h->avatar_id() != 0) avatar_id_ = h->avatar_id();
      ++counters_.handoffs;
      logOwn(now_ns, h->tick(), true);
      return;
    }
    case proto::Message::Leaderboard: {
      const auto* rows = d.msg_as_Leaderboard()->rows();
      ++counters_.leaderboards;
      counters_.leaderboard_rows = rows ? rows->size() : 0;
      counters_.leaderboard_top = rows && rows->size() > 0 ? rows->Get(0)->score() : 0;
      for (std::size_t i = 1; rows && i < rows->size(); ++i)
        if (rows->Get(i)->score() > rows->Get(i - 1)->score()) {
          ++counters_.leaderboards_unordered;
          break;
        }
      return;
    }
    case proto::Message::TransactionOutcome: {
      const proto::TransactionOutcome* o = d.msg_as_TransactionOutcome();
      transactions_.onOutcome(o->seq(), o->status(), now_ns);
      return;
    }
    case proto::Message::Pong: {
      std::int64_t sent_us = std::int64_t(d.msg_as_Pong()->client_time_us());
      double rtt_ms = double(now_ns / 1000 - sent_us) * 1e-3;
      // A Pong echoes our own clock; anything negative or ancient is not ours.
      if (rtt_ms >= 0 && rtt_ms < 60'000) {
        counters_.rtt_ms.add(rtt_ms);
        counters_.last_rtt_ms = rtt_ms;
      }
      ++counters_.pongs;
      setDilation(d.msg_as_Pong()->dilation(), now_ns);
      return;
    }
    default:
      counters_.drops.add(gateway::DropReason::UnexpectedType);
      return;
  }
}

}  // namespace zonesim::clients
