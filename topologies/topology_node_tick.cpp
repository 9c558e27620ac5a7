// One tick of a node: its input, its step (a host steps everyone), the states it sends, the
// hits it claims, a peer's vote and tally, its cheats, and its views for the benchmark.
#include <cmath>

#include "common/interest_grid.h"
#include "topologies/node_rules.h"
#include "topologies/state_frame.h"
#include "topologies/topology_node.h"
#include "topologies/vote_frame.h"
#include "wire/wire_encode.h"
#include "zone_node/systems/avatar_movement.h"

namespace zonesim::topo {

using namespace rules;

namespace {

double planarDistance(const dr::V3& a, const dr::V3& b) {
  return std::hypot(a.x - b.x, a.z - b.z);
}

// A teleport's jump along x: forward unless that leaves the arena.
double teleportStep(const SceneBox& world, const dr::V3& pos) {
  return pos.x + kTeleportMetres < world.max.x - 1 ? kTeleportMetres : -kTeleportMetres;
}

}  // namespace

void TopologyNode::tick(std::uint64_t t) {
  bool cheating = config_.cheat_seconds <= 0 || double(t) * scene_.dt < config_.cheat_seconds;
  cheats_ = cheating ? config_.cheats : Cheats{};
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
    double f = cheats_.speed ? kSpeedHackFactor : 1.0;
    // The client's Input carries no acknowledgements: the host resends nothing.
    std::vector<std::uint8_t> input =
        gateway::encodeInput(config_.token, ++seq_, float(move.x * f), float(move.z * f));
    for (const Registration* r : recipients()) send(r->address, input);
  } else {
    stepOwn(t, move);
  }
  if (cheats_.teleport && t % kTeleportEveryTicks == kTeleportEveryTicks - 1) cheatTeleport(t);
  if (config_.role != Role::Client) sendStates(t);
  if (config_.role == Role::Peer) {
    tallyVotes(t);
    if (t % kVoteEveryTicks == config_.player % kVoteEveryTicks) sendVote(t);
  }
  claimHits(t);
  if (t % kViewEveryTicks == 0) logViews(t);
}

void TopologyNode::stepOwn(std::uint64_t t, const Move& move) {
  double accel = zone::kAvatarAccel * (cheats_.speed ? kSpeedHackFactor : 1.0);
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
  double dx = teleportStep(scene_.world, own_.pos);
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
  for (const Registration* r : recipients()) send(r->address, forged);
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
  std::vector<const Registration*> to = recipients();
  // An equivocator shows the lowest-numbered share of the others a teleport every other 2 s,
  // jumping there and back, and the rest the truth.
  std::size_t fooled = 0;
  if (cheats_.equivocate && (t + 1) / kTeleportEveryTicks % 2 == 1) {
    fooled = std::size_t(std::lround(kEquivocateShare * double(to.size())));
    entities[0].state.pos.x += teleportStep(scene_.world, own_.pos);
  }
  std::vector<std::uint8_t> lie =
      fooled ? encodeStateFrame(codec_, config_.token, seq_, t + 1, entities) : frame;
  for (std::size_t i = 0; i < to.size(); ++i) send(to[i]->address, i < fooled ? lie : frame);
}

void TopologyNode::tallyVotes(std::uint64_t t) {
  // This peer's own verdict is its vote too, counted like everyone else's.
  tally_.record({config_.player, t, verdict_.at(t)});
  for (std::uint32_t p = 0; p < config_.players; ++p) {
    if (p == config_.player) continue;
    bool now = tally_.excluded(p, t);
    if (now == excluded(p)) continue;
    if (now) {
      excluded_.insert(p);
      excluded_since_.emplace(p, t);
    } else {
      excluded_.erase(p);
      readmitted_at_[p] = t;
    }
  }
}

void TopologyNode::sendVote(std::uint64_t t) {
  if (cheats_.vote) return cheatVote(t);
  Suspects suspects = verdict_.at(t);
  // Votes against no one are sent once, to withdraw the last one (its expiry covers a loss).
  if (!suspects && !voted_against_anyone_) return;
  voted_against_anyone_ = suspects != 0;
  std::vector<std::uint8_t> vote = encodeVote({config_.player, t, suspects}, config_.token);
  for (const Registration* r : recipients()) send(r->address, vote);
  ++votes_sent_;
}

void TopologyNode::cheatVote(std::uint64_t t) {
  // A liar votes against every other player, and forges votes: one in another player's name
  // against everyone else (turn by turn) and one that is not keyed by the game's token.
  Suspects everyone = config_.players == 64 ? ~Suspects{0} : suspectBit(config_.players) - 1;
  std::uint32_t victim =
      std::uint32_t((config_.player + 1 + t / kVoteEveryTicks) % config_.players);
  if (victim == config_.player) victim = (victim + 1) % config_.players;
  std::vector<std::uint8_t> lie =
      encodeVote({config_.player, t, everyone & ~suspectBit(config_.player)}, config_.token);
  std::vector<std::uint8_t> impersonation =
      encodeVote({victim, t, everyone & ~suspectBit(victim)}, config_.token);
  std::vector<std::uint8_t> unkeyed =
      encodeVote({config_.player, t, everyone & ~suspectBit(config_.player)}, config_.token ^ 1);
  for (const Registration* r : recipients()) {
    send(r->address, lie);
    if (victim != r->player) send(r->address, impersonation);
    send(r->address, unkeyed);
  }
  ++votes_sent_;
}

void TopologyNode::claimHits(std::uint64_t t) {
  bool fake = cheats_.hit;
  if (t % (fake ? kFakeHitEveryTicks : kHitEveryTicks) != config_.player % kFakeHitEveryTicks)
    return;
  std::optional<dr::V3> me = shownAt(config_.player, t);
  if (!me) return;
  std::optional<std::uint32_t> pick;
  double best = fake ? -1 : limits_.hit_reach - kHonestHitMargin;
  for (const auto& [p, s] : shown_) {
    if (p == config_.player || !s.known || excluded(p)) continue;
    double d = planarDistance(*me, *shownAt(p, t));
    if (fake ? d > best : d <= best) best = d, pick = p;
  }
  if (!pick) return;
  ++hits_claimed_;
  HitClaim hit{config_.player, *pick, t};
  std::vector<std::uint8_t> claim = encodeHit(hit, config_.token);
  if (config_.role == Role::Host) ++hits_accepted_;  // the host's word is the game's
  for (const Registration* r : recipients()) send(r->address, claim);
}

void TopologyNode::logViews(std::uint64_t t) {
  // After tick t's step the world stands at tick t + 1 (what sendStates stamps): every node
  // shows every player there, extrapolating what it last heard.
  const std::uint64_t at = t + 1;
  for (const auto& [p, s] : shown_)
    if (auto pos = shownAt(p, at); pos && !excluded(p)) log_.view(at, p, *pos);
  if (config_.role == Role::Peer) log_.view(at, config_.player, own_.pos);
}

}  // namespace zonesim::topo
