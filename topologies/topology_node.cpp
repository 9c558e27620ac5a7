#include "topologies/topology_node.h"

#include <poll.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "common/log.h"
#include "common/timer.h"
#include "dr/dr_model.h"
#include "topologies/discovery_message.h"
#include "topologies/node_rules.h"
#include "wire/downlink_frame.h"
#include "zone_node/systems/avatar_movement.h"

namespace zonesim::topo {

using namespace rules;

namespace {

std::string fixedSeconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", s);
  return text;
}

}  // namespace

TopologyNode::TopologyNode(const NodeConfig& config, const Scene& scene)
    : config_(config),
      scene_(scene),
      codec_(dr::codecParams(scene)),
      limits_{.max_speed = scene.clients.speed,
              .max_acceleration = zone::kAvatarAccel,
              .hit_reach = scene.interactions.hit_reach,
              .probation_ticks = kProbationTicks},
      checker_(limits_, scene.dt),
      script_(scene.world, config.seed ? config.seed : scene.seed, config.player,
              std::uint64_t(std::lround(scene.clients.retarget_seconds / scene.dt))),
      socket_(config.bind),
      discovery_socket_(gateway::Endpoint{config.bind.address, 0}),
      link_(config.link, config.player),
      log_(config.out_dir, config.player),
      verdict_(kVerdictTicks),
      tally_(config.players, kVoteTtlTicks) {
  if (config.player >= config.players)
    throw std::invalid_argument("--player " + std::to_string(config.player) +
                                " is not below --players " + std::to_string(config.players));
  if (config.cheats.peerOnly() && config.role != Role::Peer)
    throw std::invalid_argument("--cheat " + config.cheats.names() + ": vote and equivocate " +
                                "are a peer's cheats, not a " + roleName(config.role) + "'s");
  own_.pos = startPosition(scene.world, config.player, config.players);
}

double TopologyNode::maxSpeed() const {
  return scene_.clients.speed *
         (cheats_.speed && config_.role != Role::Client ? kSpeedHackFactor : 1.0);
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
    bodies_[p] = {startPosition(scene_.world, p, config_.players), {}};
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
  if (bytes[0] == kVoteTag) return handleVote(bytes, sender);
  if (gateway::isDownlinkFrame(bytes)) return handleStates(bytes, sender);
  handleInput(bytes, sender);
}

// ---- helpers ----

void TopologyNode::show(std::uint32_t player, std::uint64_t t, const dr::State& s) {
  Shown& shown = shown_[player];
  if (shown.known && t < shown.tick) return;  // an older state overtaken on the way
  bool moved = !shown.known || std::hypot(s.vel.x - shown.logged_vel.x,
                                          s.vel.z - shown.logged_vel.z) > kSeenVelocityChange;
  if (moved && player != config_.player && !excluded(player)) {
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

bool TopologyNode::staleAt(std::uint32_t player, std::uint64_t t) const {
  if (player == config_.player && config_.role != Role::Client) return false;
  auto it = shown_.find(player);
  return it == shown_.end() || !it->second.known || it->second.tick + kHitJudgeMaxAgeTicks < t;
}

std::optional<std::uint32_t> TopologyNode::playerAt(const gateway::Endpoint& from) const {
  for (const auto& [p, r] : directory_)
    if (r.address == from) return p;
  return std::nullopt;
}

std::vector<const Registration*> TopologyNode::recipients() const {
  // The host sends to its clients, a client to its host, a peer to every other peer.
  std::vector<const Registration*> out;
  for (const auto& [p, r] : directory_) {
    if (p == config_.player) continue;
    bool wanted = config_.role == Role::Host   ? r.role == Role::Client
                  : config_.role == Role::Peer ? r.role == Role::Peer
                                               : r.role == Role::Host;
    if (wanted) out.push_back(&r);
  }
  return out;
}

void TopologyNode::caught(std::uint32_t player) {
  verdict_.caught(player, now_tick_);
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

}  // namespace zonesim::topo
