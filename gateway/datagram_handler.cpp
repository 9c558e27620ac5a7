#include "gateway/datagram_handler.h"

#include <algorithm>

#include "common/timer.h"

namespace zonesim::gateway {

void Outbox::clear() {
  replies.clear();
  spawns.clear();
  inputs.clear();
  transactions.clear();
  leaderboards.clear();
  closed.clear();
  replaced.clear();
}

DatagramHandler::DatagramHandler(SessionTable& sessions, const HandlerConfig& config)
    : sessions_(sessions), config_(config), spawn_rng_(config.spawn_seed, 0x5a17) {
  if (config_.auth_key) gate_.emplace(*config_.auth_key, config_.gateway_id);
}

Bytes DatagramHandler::welcomeFor(const Session& s) const {
  WelcomeInfo w;
  w.client_nonce = s.client_nonce;
  w.token = s.token;
  w.player_id = s.player_id;
  w.avatar_id = s.avatar_id;
  w.zone = s.zone;
  w.tick_rate = config_.tick_rate;
  const SceneBox& b = config_.world;
  w.world_min = proto::Vec3f(float(b.min.x), float(b.min.y), float(b.min.z));
  w.world_max = proto::Vec3f(float(b.max.x), float(b.max.y), float(b.max.z));
  w.codec = config_.codec;
  w.sim_dt = config_.sim_dt;
  w.last_input_seq = s.last_input_seq;
  if (config_.resume_key) {
    auth::ResumeToken r{s.player_id, std::uint8_t(s.kind), s.address.address, s.address.port,
                        config_.unix_now_ms() + std::uint64_t(config_.resume_valid_s * 1000)};
    auth::ResumeBytes b = auth::signResume(r, *config_.resume_key);
    w.resume_token.assign(b.begin(), b.end());
  }
  return encodeWelcome(w);
}

void DatagramHandler::handle(std::span<const std::uint8_t> bytes, const Endpoint& from,
                             std::int64_t now_ns, Outbox& out) {
  Verified v = verifyDatagram(bytes, Direction::ToGateway);
  if (!v.ok()) {
    drops_.add(v.reason);
    return;
  }
  const proto::Datagram& d = *v.datagram;
  if (d.msg_type() == proto::Message::Hello) {
    onHello(d, from, bytes.size(), now_ns, out);
    return;
  }
  SlotHandle h;
  Session* s = authenticate(d, from, h);
  if (s == nullptr) return;
  // A flooding client costs the gateway no more than its share, and cannot keep its session
  // alive by flooding: a dropped datagram is not "heard".
  if (!withinRate(*s, now_ns)) {
    drops_.add(DropReason::RateLimited);
    return;
  }
  s->last_heard_ns = now_ns;
  ++s->traffic.datagrams_in;
  s->traffic.bytes_in += bytes.size();
  switch (d.msg_type()) {
    case proto::Message::Input:
      // The ack is good even when the input itself is a stale duplicate.
      s->resend.onAck(d.msg_as_Input()->ack(), d.msg_as_Input()->ack_bits(), now_ns);
      onInput(*d.msg_as_Input(), *s, out);
      return;
    case proto::Message::Ping:
      s->resend.onAck(d.msg_as_Ping()->ack(), d.msg_as_Ping()->ack_bits(), now_ns);
      out.replies.push_back(
          {from, s->token,
           encodePong(s->token, d.msg_as_Ping()->client_time_us(), wallTimeUs(), dilation_)});
      ++accepted_;
      return;
    case proto::Message::Transaction:
      onTransaction(*d.msg_as_Transaction(), *s, out);
      return;
    case proto::Message::LeaderboardQuery:
      if (!s->welcomed) {
        drops_.add(DropReason::NotReady);
        return;
      }
      out.leaderboards.push_back({s->player_id, s->zone, d.msg_as_LeaderboardQuery()->count()});
      ++accepted_;
      return;
    case proto::Message::Bye: {
      Session ended = *s;
      sessions_.erase(h);
      out.closed.push_back(std::move(ended));
      ++accepted_;
      return;
    }
    default:
      drops_.add(DropReason::UnexpectedType);
      return;
  }
}

bool DatagramHandler::withinRate(Session& s, std::int64_t now_ns) const {
  if (s.rate_tokens < 0) {
    s.rate_tokens = config_.rate_burst;
  } else {
    double refill = double(now_ns - s.rate_ns) * 1e-9 * config_.rate_per_s;
    s.rate_tokens = std::min(config_.rate_burst, s.rate_tokens + std::max(0.0, refill));
  }
  s.rate_ns = now_ns;
  if (s.rate_tokens < 1) return false;
  s.rate_tokens -= 1;
  return true;
}

Session* DatagramHandler::authenticate(const proto::Datagram& d, const Endpoint& from,
                                       SlotHandle& handle) {
  auto found = sessions_.findByToken(d.token());
  Session* s = found ? sessions_.get(*found) : nullptr;
  if (s == nullptr) {
    drops_.add(DropReason::BadToken);
    return nullptr;
  }
  // A leaked or sniffed token used from elsewhere must not steer someone else's avatar.
  if (s->address != from) {
    drops_.add(DropReason::WrongAddress);
    return nullptr;
  }
  handle = *found;
  return s;
}

void DatagramHandler::onHello(const proto::Datagram& d, const Endpoint& from, std::size_t size,
                              std::int64_t now_ns, Outbox& out) {
  std::uint64_t nonce = d.msg_as_Hello()->client_nonce();
  if (auto existing = sessions_.findByHello(from, nonce)) {
    Session* s = sessions_.get(*existing);
    s->last_heard_ns = now_ns;
    ++s->traffic.datagrams_in;
    s->traffic.bytes_in += size;
    // A retry: the Welcome (or the Hello) was lost. Never a second session for one Hello.
    if (s->welcomed) out.replies.push_back({from, s->token, welcomeFor(*s)});
    ++accepted_;
    return;
  }
  const proto::Hello& hello = *d.msg_as_Hello();
  std::span<const std::uint8_t> resume;
  if (const flatbuffers::Vector<std::uint8_t>* r = hello.resume_token()) resume = {r->data(), r->size()};
  std::optional<auth::ResumeToken> resuming;
  if (!resume.empty()) {
    resuming = checkResume(resume, from);
    if (!resuming) return;
  }
  // Before the token check: a kind this world has no speed or nimbus for never costs an HMAC.
  std::uint8_t kind = resuming ? resuming->kind : hello.kind();
  if (kind >= kPlayerKindCount || (config_.kinds & (std::uint32_t{1} << kind)) == 0) {
    drops_.add(DropReason::UnknownKind);
    return;
  }
  // After the retry check: a lost Welcome is resent to the address the token was checked for.
  // A resumed player was admitted when it first came: no connect token again.
  std::optional<Admitted> admitted;
  if (gate_ && !resuming) {
    const flatbuffers::Vector<std::uint8_t>* t = hello.connect_token();
    std::span<const std::uint8_t> token;
    if (t != nullptr) token = {t->data(), t->size()};
    DropReason refused = DropReason::TokenForged;
    admitted = gate_->check(token, from, config_.unix_now_ms(), refused);
    if (!admitted) {
      drops_.add(refused);
      return;
    }
  }
  std::optional<std::uint64_t> player;
  if (resuming) {
    player = resuming->player_id;
    // The player thought this gateway dead while it was not (a long outage of its link): the
    // old session gives way, and its avatar goes on under the new one.
    if (auto old = sessions_.findByPlayer(*player)) {
      out.replaced.push_back(*sessions_.get(*old));
      sessions_.erase(*old);
    }
  } else if (admitted) {
    player = admitted->player_id;
  }
  auto created = sessions_.create(from, nonce, now_ns, player);
  if (!created) {
    drops_.add(DropReason::SessionLimit);
    return;
  }
  if (admitted) gate_->consume(*admitted);
  Session* s = sessions_.get(*created);
  const SceneBox& b = config_.world;
  s->spawn_x = spawn_rng_.uniform(b.min.x, b.max.x);
  s->spawn_z = spawn_rng_.uniform(b.min.z, b.max.z);
  s->kind = PlayerKindId(kind);
  s->traffic.datagrams_in = 1;
  s->traffic.bytes_in = size;
  // A resumed player's zone knows it: the request re-announces its avatar where it is.
  out.spawns.push_back({s->player_id, float(s->spawn_x), 0.0f, float(s->spawn_z), kind,
                        resuming.has_value(), s->session_id});
  s->resumed = resuming.has_value();
  ++accepted_;
}

std::optional<auth::ResumeToken> DatagramHandler::checkResume(std::span<const std::uint8_t> token,
                                                              const Endpoint& from) {
  if (!config_.resume_key) {
    drops_.add(DropReason::ResumeForged);
    return std::nullopt;
  }
  auth::ResumeVerdict v = auth::checkResume(token, *config_.resume_key, from.address, from.port,
                                            config_.unix_now_ms());
  switch (v.check) {
    case auth::ResumeCheck::Ok:
      return v.token;
    case auth::ResumeCheck::Forged:
      drops_.add(DropReason::ResumeForged);
      break;
    case auth::ResumeCheck::Expired:
      drops_.add(DropReason::ResumeExpired);
      break;
    case auth::ResumeCheck::WrongAddress:
      drops_.add(DropReason::ResumeWrongAddress);
      break;
  }
  return std::nullopt;
}

void DatagramHandler::onInput(const proto::Input& in, Session& s, Outbox& out) {
  if (!s.welcomed) {
    drops_.add(DropReason::NotReady);
    return;
  }
  // Zones apply each seq once, in order: duplicates and late reorderings are useless to them.
  if (in.seq() <= s.last_input_seq) {
    drops_.add(DropReason::StaleInput);
    return;
  }
  // Earlier ones whose own datagrams never came go first, in order: the zone applies each
  // seq once and holds a gap only briefly.
  if (const auto* earlier = in.earlier()) {
    for (const proto::InputMove* e : *earlier) {
      if (e->seq() <= s.last_input_seq) continue;
      forwardInput({e->seq(), e->move_x(), e->move_z()}, s, out);
      ++inputs_recovered_;
    }
  }
  forwardInput({in.seq(), in.move_x(), in.move_z()}, s, out);
  ++accepted_;
}

void DatagramHandler::forwardInput(const InputRecord& in, Session& s, Outbox& out) {
  s.last_input_seq = in.seq;
  s.inputs.record(in);
  ++s.traffic.inputs_forwarded;
  out.inputs.push_back({s.player_id, s.avatar_id, s.zone, in.seq, in.move_x, in.move_z});
}

void DatagramHandler::onTransaction(const proto::Transaction& t, Session& s, Outbox& out) {
  if (!s.welcomed) {
    drops_.add(DropReason::NotReady);
    return;
  }
  // Every copy goes on, repeats too: the zone answers a repeat with the outcome the client
  // missed, and only the zone knows what it applied.
  out.transactions.push_back({s.player_id, s.zone, transactionInfo(t)});
  ++accepted_;
}

}  // namespace zonesim::gateway
