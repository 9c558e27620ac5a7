// The rigid bodies' step in a cluster: islands found across zones (body_islands.h), each
// stepped whole by the rank holding its lowest id, and what a body's next step needs from its
// last carried in its record (BodyData: rest time, sleep group, cached contacts).

#include <algorithm>
#include <bit>
#include <cmath>
#include <unordered_map>

#include "common/scene.h"
#include "common/timer.h"
#include "physics/aabb.h"
#include "physics/cloth.h"
#include "physics/world.h"
#include "zone_node/cluster/entity_codec.h"
#include "zone_node/systems/body_islands.h"
#include "zone_node/systems/rigid_bodies.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

namespace {

// A recycled contact's origin and materials as the entity store carries them, in the
// contact's own body order (the lower index first, as in every world built from the store).
CachedContactOrigin carriedOrigin(const physics::BodyContact& c,
                                  const physics::ManifoldOrigin& origin) {
  CachedContactOrigin o;
  o.normal = c.manifold.normal;
  o.first_position = origin.a.position;
  o.first_orientation = origin.a.orientation;
  o.second_position = origin.b.position;
  o.second_orientation = origin.b.orientation;
  o.points.assign(origin.point.begin(), origin.point.begin() + c.manifold.count);
  o.depths.assign(origin.depth.begin(), origin.depth.begin() + c.manifold.count);
  o.friction = c.friction;
  o.restitution = c.restitution;
  o.rolling = c.rolling;
  return o;
}

// Puts a carried origin back (into `origins`, when its points are the contact's), so the rebuilt
// world may recycle the contact as the old one would.
void restoreOrigin(const CachedContactOrigin& o, physics::BodyContact& c,
                   std::vector<physics::ManifoldOrigin>& origins) {
  c.manifold.normal = o.normal;
  if (int(o.points.size()) == c.manifold.count && o.depths.size() == o.points.size()) {
    physics::ManifoldOrigin& origin = origins.emplace_back();
    origin.a = {o.first_position, o.first_orientation};
    origin.b = {o.second_position, o.second_orientation};
    for (int p = 0; p < c.manifold.count; ++p) {
      origin.point[p] = o.points[p];
      origin.depth[p] = o.depths[p];
    }
    c.origin = std::uint32_t(origins.size() - 1);
  }
  c.friction = o.friction;
  c.restitution = o.restitution;
  c.rolling = o.rolling;
}

// Added to every reach box (m): covers velocity changes within the tick that the twice-the-
// travel margin does not (contacts, explosions, kinematic pushes of a few m/s).
constexpr double kReachSlack = 0.05;

/// True when `box`, grown by pad, reaches out of the zone's rectangle on the ground plane.
bool nearBorder(const physics::Aabb& box, double pad, const ZoneRect& zone) {
  return box.lo.x() - pad < zone.min_x || box.hi.x() + pad >= zone.max_x ||
         box.lo.z() - pad < zone.min_z || box.hi.z() + pad >= zone.max_z;
}

}  // namespace

std::size_t RigidBodySystem::advanceInCluster(StepContext& ctx) {
  Stopwatch border;
  EntityStore& store = ctx.store;
  const Collectives& cluster = ctx.cluster;
  const std::vector<std::size_t> own = bodiesById(store);
  ctx.counters.bodies_checked = own.size();

  // Reach boxes: the bounds each body may sweep, with the contact margin, this tick.
  const double margin = physics::WorldSettings{}.contact_margin;
  const double gravity = physics::ForceModel{}.gravity.norm();
  std::vector<EntityId> ids;
  std::vector<physics::Aabb> boxes;
  std::vector<IndexLink> links;
  double widest = 0;
  for (std::size_t i : own) {
    const double travel = 2.0 * (store.vel[i].norm() + gravity * ctx.dt) * ctx.dt;
    const physics::Aabb box =
        physics::shapeBounds(shapeOf(store.id[i], store.body[i]), store.pos[i], store.rot[i])
            .expanded(margin + travel + kReachSlack);
    widest = std::max({widest, box.hi.x() - box.lo.x(), box.hi.z() - box.lo.z()});
    ids.push_back(store.id[i]);
    boxes.push_back(box);
  }
  auto ownIndex = [&](EntityId id) -> std::optional<std::uint32_t> {
    auto it = std::lower_bound(ids.begin(), ids.end(), id);
    if (it == ids.end() || *it != id) return std::nullopt;
    return std::uint32_t(it - ids.begin());
  };
  for (const auto& [a, b] : joint_links_)
    if (auto ia = ownIndex(a), ib = ownIndex(b); ia && ib) links.emplace_back(*ia, *ib);
  const std::vector<EntityId> label = joinOverlapping(ids, boxes, links);

  // A body of another zone can reach ours only if our body lies within the widest reach box
  // of the cluster from the border: share those, and join the islands they link. Jointed
  // bodies are always shared (their partner may be anywhere), and so are bodies that may touch
  // a cloth: the cloths' rank sends their reach boxes with the widest box.
  const std::vector<BorderBody> cloths = clothBoxes(ctx);
  std::uint64_t awake = 0;
  for (std::size_t i : own) awake += !store.body[i].sleeping;
  std::vector<std::uint64_t> first = {std::bit_cast<std::uint64_t>(widest), awake, cloths.size()};
  for (const BorderBody& c : cloths) appendWords(c, first);
  double pad = 0;
  std::uint64_t awake_anywhere = 0;
  std::vector<BorderBody> cloth_boxes;
  {
    // Each rank's list: its widest box, its awake bodies, its number of cloths, their records.
    const std::vector<std::uint64_t> got = cluster.gather(first);
    for (std::size_t at = 0; at + 3 <= got.size();) {
      pad = std::max(pad, std::bit_cast<double>(got[at]));
      awake_anywhere += got[at + 1];
      const std::size_t words = std::size_t(got[at + 2]) * kBorderBodyWords;
      if (at + 3 + words > got.size())
        throw std::runtime_error("island exchange: a rank's cloth list runs past the gather");
      for (const BorderBody& c : borderBodiesOf(std::span(got).subspan(at + 3, words)))
        cloth_boxes.push_back(c);
      at += 3 + words;
    }
  }
  // Every body of the cluster asleep and nothing to wake one: no world would step (as one
  // world holding them all would not), so the rest of the exchange is skipped everywhere.
  if (awake_anywhere == 0 && cloths_.empty() && !set_pieces_.moving() &&
      !explosionDue(ctx.tick, ctx.dt)) {
    border_time_ += border.elapsedSeconds();
    return 0;
  }
  std::vector<std::uint64_t> words;
  for (std::size_t k = 0; k < own.size(); ++k) {
    bool share = nearBorder(boxes[k], pad, cluster.zone) || jointed_.count(ids[k].value) > 0;
    for (const BorderBody& c : cloth_boxes) share = share || c.box.overlaps(boxes[k]);
    if (share) appendWords(BorderBody{label[k], ids[k], cluster.rank, boxes[k]}, words);
  }
  for (const BorderBody& c : cloths) appendWords(c, words);
  const std::unordered_map<std::uint64_t, IslandSolver> solver =
      joinAcrossZones(borderBodiesOf(cluster.gather(words)), joint_links_);
  ctx.counters.island_exchanges = 1;

  // Each body goes to the rank solving its island; the visitors come here.
  const auto ranks = std::size_t(cluster.ranks);
  std::vector<MigrationPayload> away(ranks);
  std::vector<BodyRef> bodies;
  std::size_t sent = 0;
  for (std::size_t k = 0; k < own.size(); ++k) {
    auto it = solver.find(label[k].value);
    const int to = it == solver.end() ? cluster.rank : it->second.rank;
    if (to == cluster.rank) {
      bodies.push_back({&store, own[k]});
    } else {
      away[std::size_t(to)].entities.push_back(store.record(own[k]));
      ++sent;
    }
  }
  std::vector<std::vector<std::uint8_t>> out(ranks);
  for (std::size_t r = 0; r < ranks; ++r) {
    if (away[r].entities.empty()) continue;
    away[r].tick = ctx.tick;
    away[r].from_rank = cluster.rank;
    out[r] = encodeMigration(away[r]);
  }
  std::vector<std::vector<std::uint8_t>> in = cluster.swap(out);
  visitors_ = EntityStore{};
  std::vector<int> visitor_from;
  for (std::size_t r = 0; r < ranks; ++r) {
    if (in[r].empty()) continue;
    for (const EntityRecordData& e : decodeMigration(in[r]).entities) {
      visitors_.add(e);
      visitor_from.push_back(int(r));
    }
  }
  for (std::size_t v = 0; v < visitors_.size(); ++v) bodies.push_back({&visitors_, v});
  std::sort(bodies.begin(), bodies.end(),
            [](const BodyRef& a, const BodyRef& b) { return a.id() < b.id(); });
  ctx.counters.island_bodies_in = visitors_.size();
  ctx.counters.island_bodies_out = sent;
  border_time_ += border.elapsedSeconds();

  if (!bodies.empty() || holdsCloths(ctx)) {
    holdBodies(bodies, true);
    if (stepWorld(ctx) || holdsCloths(ctx)) writeBack(bodies, true);
  } else {
    world_.reset();
    members_ = {};
  }

  // The visitors go home with their new state.
  Stopwatch back;
  for (auto& o : out) o.clear();
  std::vector<MigrationPayload> home(ranks);
  for (std::size_t v = 0; v < visitors_.size(); ++v)
    home[std::size_t(visitor_from[v])].entities.push_back(visitors_.record(v));
  for (std::size_t r = 0; r < ranks; ++r) {
    if (home[r].entities.empty()) continue;
    home[r].tick = ctx.tick;
    home[r].from_rank = cluster.rank;
    out[r] = encodeMigration(home[r]);
  }
  in = cluster.swap(out);
  for (std::size_t r = 0; r < ranks; ++r) {
    if (in[r].empty()) continue;
    for (const EntityRecordData& e : decodeMigration(in[r]).entities) {
      const std::optional<std::size_t> i = store.indexOf(e.id);
      if (!i || store.kind[*i] != EntityKind::RigidBody)
        throw std::runtime_error("rank " + std::to_string(r) + " returned body " + toString(e.id) +
                                 ", which zone " + std::to_string(cluster.rank) + " does not hold");
      store.pos[*i] = e.pos;
      store.vel[*i] = e.vel;
      store.rot[*i] = e.rot;
      store.body[*i] = e.body;
    }
  }
  border_time_ += back.elapsedSeconds();
  awake = 0;
  for (std::size_t i : own) awake += !store.body[i].sleeping;
  return awake;
}

std::vector<BorderBody> RigidBodySystem::clothBoxes(const StepContext& ctx) {
  std::vector<BorderBody> out;
  if (cloths_.empty()) return out;
  if (cloth_rank_ < 0) {
    const Vec3& p = cloths_.front()->positions().front();
    const std::vector<std::uint64_t> claims =
        ctx.cluster.gather({ctx.cluster.zone.contains(p.x(), p.z()) ? 1u : 0u});
    cloth_rank_ = 0;
    for (std::size_t r = 0; r < claims.size(); ++r) {
      if (claims[r] == 0) continue;
      cloth_rank_ = int(r);
      break;
    }
  }
  if (ctx.cluster.rank != cloth_rank_) return out;
  const double margin = physics::WorldSettings{}.contact_margin;
  const double gravity = physics::ForceModel{}.gravity.norm();
  for (const auto& cloth : cloths_) {
    physics::Aabb box{cloth->positions().front(), cloth->positions().front()};
    double fastest = 0;
    for (const Vec3& p : cloth->positions()) box = box.merged({p, p});
    for (const Vec3& v : cloth->velocities()) fastest = std::max(fastest, v.norm());
    const double travel = 2.0 * (fastest + gravity * ctx.dt) * ctx.dt;
    out.push_back({EntityId{}, EntityId{}, cloth_rank_,
                   box.expanded(cloth->desc().thickness + margin + travel + kReachSlack)});
  }
  return out;
}

void RigidBodySystem::importCarried(const std::vector<BodyRef>& bodies) {
  std::unordered_map<std::uint64_t, physics::BodyIndex> index_of;
  for (std::size_t n = 0; n < bodies.size(); ++n)
    index_of[bodies[n].id().value] = physics::BodyIndex(first_dynamic_ + n);
  // Sleep: a group is named by its lowest body here (its root, when the root is here too).
  std::unordered_map<std::uint64_t, std::uint32_t> group_index;
  physics::WarmStarts warm;
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    const BodyData& b = bodies[n].store->body[bodies[n].index];
    const auto self = physics::BodyIndex(first_dynamic_ + n);
    physics::SleepState sleep;
    sleep.asleep = b.sleeping;
    sleep.rest_time = b.rest_time;
    if (b.sleeping) {
      auto root = index_of.find(b.sleep_group.value);
      sleep.group =
          group_index.try_emplace(b.sleep_group.value, root != index_of.end() ? root->second : self)
              .first->second;
    }
    world_->setSleepState(self, sleep);
    for (const CachedContact& c : b.contacts) {
      physics::BodyContact contact;
      if (c.world_body >= 0) {
        if (c.world_body >= std::int32_t(first_dynamic_)) continue;  // not a static body here
        contact.a = physics::BodyIndex(c.world_body);
        contact.b = self;
        contact.piece_a = c.piece_other;
        contact.piece_b = c.piece_self;
      } else {
        auto other = index_of.find(c.other.value);
        if (other == index_of.end()) continue;  // in another island now: no contact to warm
        contact.a = self;
        contact.b = other->second;
        contact.piece_a = c.piece_self;
        contact.piece_b = c.piece_other;
      }
      contact.manifold.count = int(c.points.size());
      for (std::size_t p = 0; p < c.points.size(); ++p) {
        contact.manifold.points[p].position = c.points[p].position;
        contact.manifold.points[p].feature = c.points[p].feature;
        contact.impulse[p] = c.points[p].impulse;
      }
      contact.rolling_impulse = c.rolling_impulse;
      if (c.origin) restoreOrigin(*c.origin, contact, warm.origins);
      warm.contacts.push_back(contact);
    }
  }
  std::sort(warm.contacts.begin(), warm.contacts.end());
  world_->setWarmStarts(warm);
  for (const JointSlot& slot : joint_slots_) {
    const BodyRef& r = bodies[slot.holder - first_dynamic_];
    for (const CachedJoint& j : r.store->body[r.index].joints) {
      if (j.joint != slot.scene) continue;
      setJointWarmStart(slot, j.impulses);
      break;
    }
  }
}

void RigidBodySystem::setJointWarmStart(const JointSlot& slot, const std::vector<double>& v) {
  using Type = SceneJoint::Type;
  if (Type(slot.type) == Type::Distance) {
    if (v.size() == 1) world_->setDistanceJointWarmStart(slot.index, v[0]);
    return;
  }
  std::array<double, physics::RigidJoints::kWarmValues> values{};
  if (v.size() != values.size()) return;  // not this kind's: start cold
  std::copy(v.begin(), v.end(), values.begin());
  if (Type(slot.type) == Type::Ball) {
    world_->setBallJointWarmStart(slot.index, values);
  } else {
    world_->setHingeJointWarmStart(slot.index, values);
  }
}

std::vector<double> RigidBodySystem::jointWarmStart(const JointSlot& slot) const {
  using Type = SceneJoint::Type;
  if (Type(slot.type) == Type::Distance) return {world_->distanceJointWarmStart(slot.index)};
  const auto values = Type(slot.type) == Type::Ball ? world_->ballJointWarmStart(slot.index)
                                                    : world_->hingeJointWarmStart(slot.index);
  return {values.begin(), values.end()};
}

void RigidBodySystem::exportCarried(const std::vector<BodyRef>& bodies) {
  auto bodyOf = [&](physics::BodyIndex i) -> BodyData& {
    const BodyRef& r = bodies[i - first_dynamic_];
    return r.store->body[r.index];
  };
  const auto last = physics::BodyIndex(first_dynamic_ + bodies.size());
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    const auto self = physics::BodyIndex(first_dynamic_ + n);
    const physics::SleepState sleep = world_->sleepState(self);
    BodyData& b = bodyOf(self);
    b.rest_time = sleep.rest_time;
    b.sleep_group = {};
    if (sleep.asleep && sleep.group >= first_dynamic_ && sleep.group < last)
      b.sleep_group = body_entity_[sleep.group - first_dynamic_];
    b.contacts.clear();
    b.joints.clear();
  }
  for (const JointSlot& slot : joint_slots_)
    bodyOf(slot.holder).joints.push_back({slot.scene, jointWarmStart(slot)});
  physics::WarmStarts warm;
  world_->warmStarts(warm);
  for (const physics::BodyContact& c : warm.contacts) {
    // The lower-id body keeps it; a static body (ground, walls, set pieces) comes first.
    const bool with_static = c.a < first_dynamic_;
    if (c.b < first_dynamic_ || c.b >= last || (!with_static && c.a >= last)) continue;
    CachedContact cached;
    if (with_static) {
      cached.world_body = std::int32_t(c.a);
      cached.piece_self = c.piece_b;
      cached.piece_other = c.piece_a;
    } else {
      cached.other = body_entity_[c.b - first_dynamic_];
      cached.piece_self = c.piece_a;
      cached.piece_other = c.piece_b;
    }
    for (int p = 0; p < c.manifold.count; ++p) {
      cached.points.push_back(
          {c.manifold.points[p].position, c.manifold.points[p].feature, c.impulse[p]});
    }
    cached.rolling_impulse = c.rolling_impulse;
    if (c.origin != physics::kNoOrigin) cached.origin = carriedOrigin(c, warm.origins[c.origin]);
    bodyOf(with_static ? c.b : c.a).contacts.push_back(std::move(cached));
  }
}

}  // namespace zonesim::zone
