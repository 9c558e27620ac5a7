#include "zone_node/cluster/entity_codec.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <variant>

#include "entity_record_generated.h"

namespace zonesim::zone {

namespace fb = zonesim::rec;

namespace {

fb::Vec3d toFb(const Vec3& v) {
  return fb::Vec3d(v.x(), v.y(), v.z());
}
fb::Quatd toFb(const Quat& q) {
  return fb::Quatd(q.x(), q.y(), q.z(), q.w());
}
Vec3 fromFb(const fb::Vec3d* v) {
  return v ? Vec3(v->x(), v->y(), v->z()) : Vec3::Zero();
}
Quat fromFb(const fb::Quatd* q) {
  return q ? Quat(q->w(), q->x(), q->y(), q->z()) : Quat::Identity();
}

// crowd_kind is CrowdState's index: the schema's numbers hold only while the order does.
static_assert(std::is_same_v<std::variant_alternative_t<1, CrowdState>, FormationMemberData> &&
              std::is_same_v<std::variant_alternative_t<2, CrowdState>, AntData> &&
              std::is_same_v<std::variant_alternative_t<3, CrowdState>, RoadTripData>);

/// A crowd state laid out in the schema's crowd_* fields.
struct CrowdFields {
  std::int32_t mode = 0, at = 0;
  double x = 0, z = 0;
  const std::vector<std::int32_t>* path = nullptr;
  const std::vector<std::int32_t>* seen = nullptr;
};

CrowdFields crowdFields(const CrowdState& s) {
  CrowdFields c;
  if (const auto* m = std::get_if<FormationMemberData>(&s)) {
    c = {m->mode, m->path_at, m->planned_x, m->planned_z, &m->path, nullptr};
  } else if (const auto* a = std::get_if<AntData>(&s)) {
    c = {a->mode, a->route_at, a->route_length, 0, &a->route, &a->dead_ends};
  } else if (const auto* t = std::get_if<RoadTripData>(&s)) {
    c.mode = t->goal;
    c.at = t->next_node;
  }
  return c;
}

std::vector<std::int32_t> cellList(const flatbuffers::Vector<std::int32_t>* v) {
  if (!v) return {};
  if (v->size() % 2 != 0) throw CodecError("npc record with an odd cell list");
  return {v->begin(), v->end()};
}

void decodeCrowd(const fb::NpcState& n, CrowdState& s) {
  switch (n.crowd_kind()) {
    case 0:
      s = std::monostate{};
      return;
    case 1:
      s = FormationMemberData{n.crowd_mode(), n.crowd_at(), n.crowd_x(), n.crowd_z(),
                              cellList(n.crowd_path())};
      return;
    case 2:
      s = AntData{n.crowd_mode(), n.crowd_at(), n.crowd_x(), cellList(n.crowd_path()),
                  cellList(n.crowd_seen())};
      return;
    case 3:
      s = RoadTripData{n.crowd_at(), n.crowd_mode()};
      return;
  }
  throw CodecError("npc record with an unknown crowd state kind " +
                   std::to_string(int(n.crowd_kind())));
}

flatbuffers::Offset<fb::EntityRecord> encodeEntity(flatbuffers::FlatBufferBuilder& b,
                                                   const EntityRecordData& r) {
  flatbuffers::Offset<fb::NpcState> npc;
  flatbuffers::Offset<fb::AvatarState> avatar;
  flatbuffers::Offset<fb::BodyState> body;
  flatbuffers::Offset<fb::EmitterState> emitter;
  switch (r.kind) {
    case EntityKind::Npc: {
      fb::Vec3d wp = toFb(r.npc.waypoint);
      fb::Vec3d gp = toFb(r.npc.gather_point);
      // The crowd state goes in the schema's crowd_* fields, as its kind lays them out.
      CrowdFields c = crowdFields(r.npc.crowd);
      flatbuffers::Offset<flatbuffers::Vector<std::int32_t>> path, seen;
      if (c.path && !c.path->empty()) path = b.CreateVector(*c.path);
      if (c.seen && !c.seen->empty()) seen = b.CreateVector(*c.seen);
      npc = fb::CreateNpcState(
          b, &wp, r.npc.max_speed, r.npc.accel, r.npc.waypoint_radius, r.npc.arrive_distance,
          r.npc.separation_radius, r.npc.separation_weight, &gp, r.npc.gather_radius,
          r.npc.gather_start, r.npc.gather_end, r.npc.gathering, r.npc.population, c.mode, c.at,
          c.x, c.z, path, seen, std::uint8_t(r.npc.crowd.index()));
      break;
    }
    case EntityKind::Avatar:
      avatar =
          fb::CreateAvatarState(b, r.avatar.player_id, r.avatar.last_input_seq, r.avatar.move_x,
                                r.avatar.move_z, r.avatar.max_speed, r.avatar.announced);
      break;
    case EntityKind::RigidBody: {
      fb::Vec3d w = toFb(r.body.angular_velocity), h = toFb(r.body.half_extents);
      body = fb::CreateBodyState(b, r.body.radius, r.body.mass, r.body.restitution, &w,
                                 r.body.sleeping, r.body.shape, &h, r.body.half_height,
                                 r.body.friction, r.body.linear_damping, r.body.angular_damping);
      break;
    }
    case EntityKind::Emitter:
      emitter = fb::CreateEmitterState(b, r.emitter.rate, r.emitter.lifetime, r.emitter.speed,
                                       r.emitter.spawn_accumulator, r.emitter.drag,
                                       r.emitter.restitution, r.emitter.max_particles);
      break;
  }
  flatbuffers::Offset<fb::AgentState> agent;
  if (r.agent.type >= 0) {
    const AgentData& a = r.agent;
    auto entered = b.CreateVector(a.entered, AgentData::kLevels);
    auto plan = b.CreateVector(a.plan, AgentData::kMaxPlan);
    auto path = b.CreateVector(a.path);
    agent = fb::CreateAgentState(b, a.type, a.state, a.step, entered, a.action, a.transitions,
                                 a.health, a.energy, a.speed_factor, a.approach, a.facts, plan,
                                 a.plan_length, a.plan_step, a.action_time, a.plan_cost, a.goal,
                                 a.nav, a.dwell, a.origin_x, a.origin_z, a.target_x, a.target_z,
                                 a.travelled, a.replans, a.arrivals, path, a.asked_tick);
  }
  fb::Vec3d pos = toFb(r.pos), vel = toFb(r.vel);
  fb::Quatd rot = toFb(r.rot);
  return fb::CreateEntityRecord(b, r.id.value, fb::EntityKind(r.kind), &pos, &vel, &rot,
                                r.rng_state, npc, avatar, body, emitter, agent);
}

template <typename T, typename V>
void copyInts(const V* from, T* to, std::size_t n, const char* what) {
  if (!from) return;
  if (from->size() != n) throw CodecError(std::string("agent record with a bad ") + what);
  for (std::size_t i = 0; i < n; ++i) to[i] = from->Get(flatbuffers::uoffset_t(i));
}

void decodeAgent(const fb::AgentState& g, AgentData& a) {
  a.type = g.type();
  a.state = g.state();
  a.step = g.step();
  copyInts(g.entered(), a.entered, AgentData::kLevels, "state entry list");
  a.action = g.action();
  a.transitions = g.transitions();
  a.health = g.health();
  a.energy = g.energy();
  a.speed_factor = g.speed_factor();
  a.approach = g.approach();
  a.facts = g.facts();
  copyInts(g.plan(), a.plan, AgentData::kMaxPlan, "plan");
  a.plan_length = g.plan_size();
  if (a.plan_length > AgentData::kMaxPlan) throw CodecError("agent record with a long plan");
  a.plan_step = g.plan_step();
  a.action_time = g.action_time();
  a.plan_cost = g.plan_cost();
  a.goal = g.goal();
  a.nav = g.nav();
  a.dwell = g.dwell();
  a.origin_x = g.origin_x();
  a.origin_z = g.origin_z();
  a.target_x = g.target_x();
  a.target_z = g.target_z();
  a.travelled = g.travelled();
  a.asked_tick = g.asked_tick();
  a.replans = g.replans();
  a.arrivals = g.arrivals();
  a.path.clear();
  if (const auto* p = g.path()) a.path.assign(p->begin(), p->end());
  if (a.path.size() % 2 != 0) throw CodecError("agent record with an odd path");
}

EntityRecordData decodeEntity(const fb::EntityRecord& e) {
  EntityRecordData r;
  r.id = EntityId{e.id()};
  auto kind = std::uint8_t(e.kind());
  if (kind >= kEntityKindCount) throw CodecError("entity record with unknown kind");
  r.kind = EntityKind(kind);
  r.pos = fromFb(e.pos());
  r.vel = fromFb(e.vel());
  r.rot = fromFb(e.rot());
  r.rng_state = e.rng_state();
  if (const fb::NpcState* n = e.npc()) {
    r.npc.waypoint = fromFb(n->waypoint());
    r.npc.max_speed = n->max_speed();
    r.npc.accel = n->accel();
    r.npc.waypoint_radius = n->waypoint_radius();
    r.npc.arrive_distance = n->arrive_distance();
    r.npc.separation_radius = n->separation_radius();
    r.npc.separation_weight = n->separation_weight();
    if (n->gather_point()) r.npc.gather_point = fromFb(n->gather_point());
    r.npc.gather_radius = n->gather_radius();
    r.npc.gather_start = n->gather_start();
    r.npc.gather_end = n->gather_end();
    r.npc.gathering = n->gathering();
    r.npc.population = n->flock();
    decodeCrowd(*n, r.npc.crowd);
  }
  if (const fb::AvatarState* a = e.avatar()) {
    r.avatar = {a->player_id(), a->last_input_seq(), a->move_x(),
                a->move_z(),    a->max_speed(),      a->announced()};
  }
  if (const fb::BodyState* s = e.body()) {
    if (s->shape() > BodyData::Capsule) throw CodecError("body record with unknown shape");
    r.body = {s->radius(),   s->mass(),  s->restitution(),          fromFb(s->angular_velocity()),
              s->sleeping(), s->shape(), fromFb(s->half_extents()), s->half_height(),
              s->friction()};
    r.body.linear_damping = s->linear_damping();
    r.body.angular_damping = s->angular_damping();
  }
  if (const fb::EmitterState* m = e.emitter()) {
    r.emitter = {m->rate(), m->lifetime(),    m->speed(),        m->spawn_accumulator(),
                 m->drag(), m->restitution(), m->max_particles()};
  }
  if (const fb::AgentState* g = e.agent()) decodeAgent(*g, r.agent);
  if (!r.id) throw CodecError("entity record without id");
  return r;
}

}  // namespace

std::vector<std::uint8_t> encodeMigration(const MigrationPayload& p) {
  flatbuffers::FlatBufferBuilder b(256 + 256 * p.entities.size());
  std::vector<flatbuffers::Offset<fb::EntityRecord>> entities;
  entities.reserve(p.entities.size());
  for (const EntityRecordData& r : p.entities) entities.push_back(encodeEntity(b, r));
  std::vector<flatbuffers::Offset<fb::ForwardedInput>> inputs;
  inputs.reserve(p.inputs.size());
  for (const ForwardedInput& in : p.inputs)
    inputs.push_back(fb::CreateForwardedInput(b, in.player_id, in.seq, in.move_x, in.move_z));
  auto root = fb::CreateMigrationBatch(b, p.tick, p.from_rank, b.CreateVector(entities),
                                       b.CreateVector(inputs));
  fb::FinishMigrationBatchBuffer(b, root);
  return {b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize()};
}

MigrationPayload decodeMigration(std::span<const std::uint8_t> bytes) {
  // Reading a Vec3d at a misaligned address is undefined even when the Verifier passed it.
  std::vector<std::uint8_t> aligned;
  if (reinterpret_cast<std::uintptr_t>(bytes.data()) % kBatchAlign != 0) {
    aligned.assign(bytes.begin(), bytes.end());  // operator new aligns for any scalar
    bytes = aligned;
  }
  // Every record is two tables; the default cap (a million tables) would refuse batches of more
  // than ~500k entities (a big checkpoint or rebalance), so the cap follows the buffer's size.
  flatbuffers::Verifier verifier(
      bytes.data(), bytes.size(), /*max_depth=*/64,
      /*max_tables=*/
      std::max<flatbuffers::uoffset_t>(1000000, flatbuffers::uoffset_t(bytes.size() / 4)));
  if (!fb::VerifyMigrationBatchBuffer(verifier))
    throw CodecError("migration batch failed verification");
  const fb::MigrationBatch* m = fb::GetMigrationBatch(bytes.data());
  MigrationPayload p;
  p.tick = m->tick();
  p.from_rank = m->from_rank();
  if (const auto* es = m->entities()) {
    p.entities.reserve(es->size());
    for (const fb::EntityRecord* e : *es) p.entities.push_back(decodeEntity(*e));
  }
  if (const auto* ins = m->inputs()) {
    for (const fb::ForwardedInput* in : *ins)
      p.inputs.push_back({in->player_id(), in->seq(), in->move_x(), in->move_z()});
  }
  return p;
}

}  // namespace zonesim::zone
