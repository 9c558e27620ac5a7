#include "topologies/topology_node.h"

#include <poll.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "common/interest_grid.h"
#include "common/log.h"
#include "common/timer.h"
#include "dr/dr_model.h"
#include "topologies/discovery_message.h"
#include "topologies/state_frame.h"
#include "wire/downlink_frame.h"
#include "wire/wire_encode.h"
#include "wire/wire_verify.h"
#include "zone_node/systems/avatar_movement.h"

namespace zonesim::topo {

namespace {

// Registrations live this long unless refreshed; refreshed every kRefreshTicks ticks, so a
// node that dies leaves the list within a few seconds.
constexpr double kRegistrationTtlSeconds = 5;
// Discovery requests and refreshes once a second at the scene's 20 Hz.
constexpr std::uint64_t kRefreshTicks = 20;
// Views are written every other tick: 10 samples a second per pair is plenty for percentiles.
constexpr std::uint64_t kViewEveryTicks = 2;
// A "seen" event is written when a player's velocity changed by more than this since the last:
// one tick of the avatar's acceleration (24 m/s^2 x 0.05 s = 1.2 m/s) passes it, the codec's
// velocity rounding (1/256 m/s) never does.
constexpr double kSeenVelocityChange = 0.25;
// Cheats: how much faster a speed hacker goes, how far and how often a teleporter jumps, how
// often a hit cheater claims a hit on the farthest player.
constexpr double kSpeedHackFactor = 3;
constexpr double kTeleportMetres = 8;
constexpr std::uint64_t kTeleportEveryTicks = 40;
constexpr std::uint64_t kFakeHitEveryTicks = 10;
// Honest players claim a hit every second on the nearest player this much inside the reach, so
// that the judges' slightly different views never reject an honest hit.
constexpr std::uint64_t kHitEveryTicks = 20;
constexpr double kHonestHitMargin = 0.5;

std::int64_t realtimeNs() {
  timespec ts{};
  clock_gettime(CLOCK_REALTIME, &ts);
  return std::int64_t(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::string fixedSeconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

double planarDistance(const dr::V3& a, const dr::V3& b) {
  return std::hypot(a.x - b.x, a.z - b.z);
}

}  // namespace

TopologyNode::TopologyNode(const NodeConfig& config, const Scene& scene)
    : config_(config),
      scene_(scene),
      codec_(dr::codecParams(scene)),
      limits_{scene.clients.speed, zone::kAvatarAccel, scene.interactions.hit_reach},
      checker_(limits_, scene.dt),
      script_(scene.world, config.seed ? config.seed : scene.seed, config.player,
              std::uint64_t(std::lround(scene.clients.retarget_seconds / scene.dt))),
      socket_(config.bind),
      discovery_socket_(gateway::Endpoint{config.bind.address, 0}),
      link_(config.link, config.player),
      log_(config.out_dir, config.player) {
  if (config.player >= config.players)
    throw std::invalid_argument("--player " + std::to_string(config.player) +
                                " is not below --players " + std::to_string(config.players));
  // Start where the script's first target is not: spread on a circle around the arena centre.
  double cx = 0.5 * (scene.world.min.x + scene.world.max.x);
  double cz = 0.5 * (scene.world.min.z + scene.world.max.z);
  double r =
      0.35 * std::min(scene.world.max.x - scene.world.min.x, scene.world.max.z - scene.world.min.z);
  double a = 2 * M_PI * double(config.player) / double(config.players);
  own_.pos = {cx + r * std::cos(a), scene.world.min.y, cz + r * std::sin(a)};
}

double TopologyNode::maxSpeed() const {
  return scene_.clients.speed *
         (config_.cheats.speed && config_.role != Role::Client ? kSpeedHackFactor : 1.0);
}

// ---- discovery ----

void TopologyNode::registerSelf() {
  std::string text = formatRequest(RegisterRequest{
      Registration{config_.player, config_.role, socket_.local()}, kRegistrationTtlSeconds});
  discovery_socket_.sendTo(config_.discovery,
                           {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

void TopologyNode::requestList() {
  std::string text = formatRequest(ListRequest{});
  discovery_socket_.sendTo(config_.discovery,
                           {reinterpret_cast<const std::uint8_t*>(text.data()), text.size()});
}

void TopologyNode::handleDiscovery(std::span<const std::uint8_t> bytes) {
  std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (text == "ok") return;
  try {
    std::map<std::uint32_t, Registration> fresh;
    for (const Registration& r : parsePeers(text)) fresh[r.player] = r;
    directory_ = std::move(fresh);
  } catch (const std::invalid_argument& e) {
    ZS_WARN("topology_node: discovery reply dropped: %s", e.what());
  }
}

bool TopologyNode::joined() const {
  std::size_t hosts = 0, peers = 0;
  for (const auto& [p, r] : directory_) {
    hosts += r.role == Role::Host;
    peers += r.role == Role::Peer;
  }
  switch (config_.role) {
    case Role::Client:
      return hosts == 1;
    case Role::Peer:
      return peers == config_.players;
    case Role::Host:
      return directory_.size() == config_.players;
  }
  return false;
}

void TopologyNode::join() {
  std::int64_t give_up = nowNs() + std::int64_t(config_.join_timeout_s * 1e9);
  while (!joined()) {
    if (nowNs() > give_up) {
      std::string what = config_.role == Role::Client
                             ? "no host registered"
                             : std::to_string(directory_.size()) + " of " +
                                   std::to_string(config_.players) + " players registered";
      throw std::runtime_error("cannot join through discovery " + config_.discovery.str() + ": " +
                               what + " within --join-timeout " +
                               fixedSeconds(config_.join_timeout_s));
    }
    registerSelf();
    requestList();
    receiveUntil(nowNs() + 100'000'000);  // monotonic: joining is not tied to the start time
  }
}

// ---- the game ----

void TopologyNode::run() {
  join();
  play();
}

void TopologyNode::play() {
  std::uint64_t ticks = std::uint64_t(std::lround(config_.duration_s / scene_.dt));
  std::int64_t dt_ns = std::int64_t(std::llround(scene_.dt * 1e9));
  std::int64_t offset = nowNs() - realtimeNs();  // tick deadlines in the monotonic clock
  for (std::uint32_t p = 0; p < config_.players && config_.role == Role::Host; ++p) {
    bodies_[p] = {};
    moves_[p] = {};
  }
  bodies_[config_.player] = own_;
  std::int64_t started = config_.start_ns + offset;
  for (std::uint64_t t = 0; t < ticks; ++t) {
    receiveUntil(config_.start_ns + std::int64_t(t) * dt_ns + offset);
    now_tick_ = t;
    tick(t);
  }
  receiveUntil(nowNs() + 200'000'000);  // the others' last datagrams
  writeSummary(double(nowNs() - started) * 1e-9);
}

void TopologyNode::receiveUntil(std::int64_t deadline_ns) {
  alignas(8) std::uint8_t buf[gateway::kMaxDatagramBytes + 1];
  auto arrived = [&](std::span<const std::uint8_t> bytes, const gateway::Endpoint& from) {
    ++datagrams_in_;
    bytes_in_ += bytes.size();
    handle(bytes, from);
  };
  for (;;) {
    // The link's held datagrams, either way, are due at their own times.
    std::int64_t wake = std::min(deadline_ns, link_.nextDueNs());
    pollfd fds[2] = {{socket_.fd(), POLLIN, 0}, {discovery_socket_.fd(), POLLIN, 0}};
    int ready = gateway::pollUntil(fds, wake);
    std::int64_t now = nowNs();
    if (link_.active()) link_.flush(socket_, now);
    while (auto r = discovery_socket_.receive(buf)) {
      if (r->from == config_.discovery && !r->truncated) handleDiscovery({buf, r->size});
    }
    while (auto r = socket_.receive(buf)) {
      if (r->truncated) {
        ++datagrams_in_;
        drop(gateway::DropReason::TooLarge, playerAt(r->from));
      } else if (link_.active()) {
        link_.receive({buf, r->size}, r->from, now);  // the downlink: lost, or held a while
      } else {
        arrived({buf, r->size}, r->from);
      }
    }
    link_.deliver(now, arrived);
    if (ready <= 0 && now >= deadline_ns) return;
  }
}

void TopologyNode::handle(std::span<const std::uint8_t> bytes, const gateway::Endpoint& from) {
  std::optional<std::uint32_t> sender = playerAt(from);
  if (!sender) return drop(gateway::DropReason::WrongAddress, sender);  // not in the game
  if (bytes.empty()) return drop(gateway::DropReason::Truncated, sender);
  if (bytes[0] == kHitTag) return handleHit(bytes, sender);
  if (gateway::isDownlinkFrame(bytes)) return handleStates(bytes, sender);
  handleInput(bytes, sender);
}

void TopologyNode::handleStates(std::span<const std::uint8_t> bytes,
                                std::optional<std::uint32_t> sender) {
  // States come from the host to its clients, and from every peer to every peer.
  bool expected = config_.role == Role::Peer ||
                  (config_.role == Role::Client && directory_.at(*sender).role == Role::Host);
  if (!expected) return drop(gateway::DropReason::UnexpectedType, sender);
  DecodedStates d = decodeStateFrame(codec_, bytes, config_.token);
  if (d.drop) return drop(*d.drop, sender);
  for (const dr::WireEntity& e : d.entities) {
    std::uint32_t player = playerOf(e.id);
    if (player == config_.player && config_.role == Role::Peer) continue;
    // A peer speaks for its own avatar only.
    if (config_.role == Role::Peer && player != *sender) {
      drop(gateway::DropReason::OutOfRange, sender);
      continue;
    }
    if (checks() &&
        checker_.checkState(player, e.tick, e.state.pos, e.state.vel) != Violation::None)
      continue;
    show(player, e.tick, e.state);
  }
}

void TopologyNode::handleHit(std::span<const std::uint8_t> bytes,
                             std::optional<std::uint32_t> sender) {
  if (config_.role == Role::Client && directory_.at(*sender).role != Role::Host)
    return drop(gateway::DropReason::UnexpectedType, sender);
  ParsedHit h = parseHit(bytes, config_.token);
  if (h.drop) return drop(*h.drop, sender);
  // A claim speaks for its sender, except the host's reports of the hits it applied.
  if (config_.role != Role::Client && h.hit.attacker != *sender)
    return drop(gateway::DropReason::OutOfRange, sender);
  std::optional<dr::V3> a = shownAt(h.hit.attacker, h.hit.tick),
                        b = shownAt(h.hit.target, h.hit.tick);
  if (!a || !b) return drop(gateway::DropReason::NotReady, sender);
  if (checks() && checker_.checkHit(h.hit.attacker, *a, *b) != Violation::None) return;
  ++hits_accepted_;
  if (config_.role == Role::Host) {
    std::vector<std::uint8_t> report = encodeHit(h.hit, config_.token);
    for (const gateway::Endpoint& to : receivers()) send(to, report);
  }
}

void TopologyNode::handleInput(std::span<const std::uint8_t> bytes,
                               std::optional<std::uint32_t> sender) {
  // Inputs go to the host alone, and it checks them exactly as the gateway does.
  if (config_.role != Role::Host) return drop(gateway::DropReason::UnexpectedType, sender);
  gateway::Verified v = gateway::verifyDatagram(bytes, gateway::Direction::ToGateway);
  if (!v.ok()) return drop(v.reason, sender);
  if (v.datagram->token() != config_.token) return drop(gateway::DropReason::BadToken, sender);
  const proto::Input* in = v.datagram->msg_as_Input();
  if (in == nullptr) return drop(gateway::DropReason::UnexpectedType, sender);
  std::uint32_t& last = input_seqs_[*sender];
  if (in->seq() <= last) return drop(gateway::DropReason::StaleInput, sender);
  last = in->seq();
  moves_[*sender] = {in->move_x(), in->move_z()};
}

void TopologyNode::tick(std::uint64_t t) {
  if (t % kRefreshTicks == 0) {
    registerSelf();
    requestList();
  }
  const dr::V3 here =
      config_.role == Role::Client ? shownAt(config_.player, t).value_or(own_.pos) : own_.pos;
  bool changed = false;
  Move move = script_.at(t, here, changed);
  if (changed) log_.input(realtimeNs(), {move.x, 0, move.z});
  if (config_.role == Role::Client) {
    double f = config_.cheats.speed ? kSpeedHackFactor : 1.0;
    // The client's Input carries no acknowledgements: the host resends nothing.
    std::vector<std::uint8_t> input =
        gateway::encodeInput(config_.token, ++seq_, float(move.x * f), float(move.z * f));
    for (const gateway::Endpoint& to : receivers()) send(to, input);
  } else {
    stepOwn(t, move);
  }
  if (config_.cheats.teleport && t % kTeleportEveryTicks == kTeleportEveryTicks - 1)
    cheatTeleport(t);
  if (config_.role != Role::Client) sendStates(t);
  claimHits(t);
  if (t % kViewEveryTicks == 0) logViews(t);
}

void TopologyNode::stepOwn(std::uint64_t t, const Move& move) {
  double accel = zone::kAvatarAccel * (config_.cheats.speed ? kSpeedHackFactor : 1.0);
  if (config_.role == Role::Host) {
    moves_[config_.player] = move;
    for (auto& [p, body] : bodies_) {
      double speed = p == config_.player ? maxSpeed() : scene_.clients.speed;
      stepAvatar(scene_.world, body, moves_[p], speed,
                 p == config_.player ? accel : zone::kAvatarAccel, scene_.dt);
      dr::State s;
      s.pos = body.pos;
      s.vel = body.vel;
      show(p, t + 1, s);
    }
    own_ = bodies_[config_.player];
    return;
  }
  stepAvatar(scene_.world, own_, move, maxSpeed(), accel, scene_.dt);
}

void TopologyNode::cheatTeleport(std::uint64_t t) {
  double dx =
      own_.pos.x + kTeleportMetres < scene_.world.max.x - 1 ? kTeleportMetres : -kTeleportMetres;
  if (config_.role != Role::Client) {
    own_.pos.x += dx;
    if (config_.role == Role::Host) bodies_[config_.player] = own_;
    return;
  }
  // A client cannot move its avatar but by input: it forges the host's state frame instead.
  std::optional<dr::V3> at = shownAt(config_.player, t);
  if (!at) return;
  dr::WireEntity e;
  e.id = avatarId(config_.player);
  e.kind = kAvatarKind;
  e.tick = t;
  e.state.pos = {at->x + dx, at->y, at->z};
  e.cell =
      InterestGrid(scene_.world, scene_.interest_cell_size).cellOf(e.state.pos.x, e.state.pos.z);
  std::vector<std::uint8_t> forged = encodeStateFrame(codec_, config_.token, 0, t, {&e, 1});
  for (const auto& [p, r] : directory_)
    if (r.role == Role::Host) send(r.address, forged);
}

void TopologyNode::sendStates(std::uint64_t t) {
  // States are sampled after the step: tick t + 1.
  InterestGrid grid(scene_.world, scene_.interest_cell_size);
  std::vector<dr::WireEntity> entities;
  auto add = [&](std::uint32_t player, const AvatarBody& b) {
    dr::WireEntity e;
    e.id = avatarId(player);
    e.kind = kAvatarKind;
    e.tick = t + 1;
    e.cell = grid.cellOf(b.pos.x, b.pos.z);
    e.state.pos = b.pos;
    e.state.vel = b.vel;
    entities.push_back(e);
  };
  if (config_.role == Role::Host) {
    for (const auto& [p, b] : bodies_) add(p, b);
  } else {
    add(config_.player, own_);
  }
  std::vector<std::uint8_t> frame =
      encodeStateFrame(codec_, config_.token, ++seq_, t + 1, entities);
  for (const gateway::Endpoint& to : receivers()) send(to, frame);
}

void TopologyNode::claimHits(std::uint64_t t) {
  bool fake = config_.cheats.hit;
  if (t % (fake ? kFakeHitEveryTicks : kHitEveryTicks) != config_.player % kFakeHitEveryTicks)
    return;
  std::optional<dr::V3> me = shownAt(config_.player, t);
  if (!me) return;
  std::optional<std::uint32_t> pick;
  double best = fake ? -1 : limits_.hit_reach - kHonestHitMargin;
  for (const auto& [p, s] : shown_) {
    if (p == config_.player || !s.known) continue;
    double d = planarDistance(*me, *shownAt(p, t));
    if (fake ? d > best : d <= best) best = d, pick = p;
  }
  if (!pick) return;
  ++hits_claimed_;
  HitClaim hit{config_.player, *pick, t};
  std::vector<std::uint8_t> claim = encodeHit(hit, config_.token);
  if (config_.role == Role::Host) ++hits_accepted_;  // the host's word is the game's
  for (const gateway::Endpoint& to : receivers()) send(to, claim);
}

void TopologyNode::logViews(std::uint64_t t) {
  // After tick t's step the world stands at tick t + 1 (what sendStates stamps): every node
  // shows every player there, extrapolating what it last heard.
  const std::uint64_t at = t + 1;
  for (const auto& [p, s] : shown_)
    if (auto pos = shownAt(p, at)) log_.view(at, p, *pos);
  if (config_.role == Role::Peer) log_.view(at, config_.player, own_.pos);
}

// ---- helpers ----

void TopologyNode::show(std::uint32_t player, std::uint64_t t, const dr::State& s) {
  Shown& shown = shown_[player];
  if (shown.known && t < shown.tick) return;  // an older state overtaken on the way
  bool moved = !shown.known || std::hypot(s.vel.x - shown.logged_vel.x,
                                          s.vel.z - shown.logged_vel.z) > kSeenVelocityChange;
  if (moved && player != config_.player) {
    log_.seen(realtimeNs(), player, s.vel);
    shown.logged_vel = s.vel;
  }
  shown.tick = t;
  shown.state = s;
  shown.known = true;
}

std::optional<dr::V3> TopologyNode::shownAt(std::uint32_t player, std::uint64_t t) const {
  if (player == config_.player && config_.role != Role::Client) return own_.pos;
  auto it = shown_.find(player);
  if (it == shown_.end() || !it->second.known) return std::nullopt;
  double ahead = (double(t) - double(it->second.tick)) * scene_.dt;
  return dr::predictPosition(it->second.state, dr::Order::First, ahead);
}

std::optional<std::uint32_t> TopologyNode::playerAt(const gateway::Endpoint& from) const {
  for (const auto& [p, r] : directory_)
    if (r.address == from) return p;
  return std::nullopt;
}

std::vector<gateway::Endpoint> TopologyNode::receivers() const {
  // The host sends to its clients, a client to its host, a peer to every other peer.
  std::vector<gateway::Endpoint> out;
  for (const auto& [p, r] : directory_) {
    if (p == config_.player) continue;
    bool wanted = config_.role == Role::Host   ? r.role == Role::Client
                  : config_.role == Role::Peer ? r.role == Role::Peer
                                               : r.role == Role::Host;
    if (wanted) out.push_back(r.address);
  }
  return out;
}

void TopologyNode::send(const gateway::Endpoint& to, std::span<const std::uint8_t> bytes) {
  bool sent = link_.active() ? link_.send(socket_, to, bytes, nowNs()) : socket_.sendTo(to, bytes);
  if (!sent) return;
  ++datagrams_out_;
  bytes_out_ += bytes.size();
}

void TopologyNode::drop(gateway::DropReason reason, std::optional<std::uint32_t> sender) {
  drops_.add(reason);
  if (sender) ++drops_by_player_[*sender];
}

void TopologyNode::writeSummary(double played_s) const {
  nlohmann::json j;
  j["player"] = config_.player;
  j["role"] = roleName(config_.role);
  j["cheat"] = config_.cheats.names();
  j["cross_check"] = config_.cross_check;
  j["played_s"] = played_s;
  j["bytes_in"] = bytes_in_;
  j["bytes_out"] = bytes_out_;
  j["datagrams_in"] = datagrams_in_;
  j["datagrams_out"] = datagrams_out_;
  j["bytes_in_per_s"] = double(bytes_in_) / played_s;
  j["bytes_out_per_s"] = double(bytes_out_) / played_s;
  j["hits_claimed"] = hits_claimed_;
  j["hits_accepted"] = hits_accepted_;
  nlohmann::json drops = nlohmann::json::object(), violations = nlohmann::json::object(),
                 detected = nlohmann::json::object();
  for (std::size_t r = 0; r < std::size_t(gateway::DropReason::Count); ++r)
    if (auto n = drops_[gateway::DropReason(r)])
      drops[gateway::dropReasonName(gateway::DropReason(r))] = n;
  for (std::size_t v = 1; v < std::size_t(Violation::Count); ++v)
    if (auto n = checker_.counts()[v]) violations[violationName(Violation(v))] = n;
  // What this node caught of each player: its drops of their datagrams and its rejections.
  for (std::uint32_t p = 0; p < config_.players; ++p) {
    auto it = drops_by_player_.find(p);
    std::uint64_t n = checker_.rejectedOf(p) + (it == drops_by_player_.end() ? 0 : it->second);
    if (n) detected[std::to_string(p)] = n;
  }
  j["drops"] = drops;
  j["violations"] = violations;
  j["detected_by_player"] = detected;
  std::string path = config_.out_dir + "/node_" + std::to_string(config_.player) + ".json";
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f << j.dump() << '\n';
}

}  // namespace zonesim::topo
