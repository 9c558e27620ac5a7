// One tick of a node: its input, its step (a host steps everyone), the states it sends, the
// hits it claims, its cheats, and its views for the benchmark.
#include <cmath>

#include "common/interest_grid.h"
#include "topologies/node_rules.h"
#include "topologies/state_frame.h"
#include "topologies/topology_node.h"
#include "wire/wire_encode.h"
#include "zone_node/systems/avatar_movement.h"

namespace zonesim::topo {

using namespace rules;

namespace {

double planarDistance(const dr::V3& a, const dr::V3& b) {
  return std::hypot(a.x - b.x, a.z - b.z);
}

}  // namespace

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

}  // namespace zonesim::topo
