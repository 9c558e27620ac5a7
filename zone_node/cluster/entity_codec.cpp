#include "zone_node/cluster/entity_codec.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <variant>

#include "common/player_kind.h"
#include "entity_record_generated.h"

namespace zonesim::zone {

namespace fb = zonesim::rec;

namespace {

using Builder = flatbuffers::FlatBufferBuilder;
using RecordBuilder = fb::EntityRecordBuilder;
using Record = fb::EntityRecord;

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

// ---- The component tables (NpcState, AvatarState, BodyState, EmitterState, AgentState) ----

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

// Each encodeX returns a null offset for an entity without that component (the table is absent).

flatbuffers::Offset<fb::NpcState> encodeNpc(Builder& b, const NpcData& n, EntityKind kind) {
  if (kind != EntityKind::Npc) return {};
  fb::Vec3d wp = toFb(n.waypoint), gp = toFb(n.gather_point);
  // The crowd state goes in the schema's crowd_* fields, as its kind lays them out.
  CrowdFields c = crowdFields(n.crowd);
  flatbuffers::Offset<flatbuffers::Vector<std::int32_t>> path, seen;
  if (c.path && !c.path->empty()) path = b.CreateVector(*c.path);
  if (c.seen && !c.seen->empty()) seen = b.CreateVector(*c.seen);
  return fb::CreateNpcState(b, &wp, n.max_speed, n.accel, n.waypoint_radius, n.arrive_distance,
                            n.separation_radius, n.separation_weight, &gp, n.gather_radius,
                            n.gather_start, n.gather_end, n.gathering, n.population, c.mode, c.at,
                            c.x, c.z, path, seen, std::uint8_t(n.crowd.index()));
}

void decodeNpc(const fb::NpcState& s, NpcData& n) {
  n.waypoint = fromFb(s.waypoint());
  n.max_speed = s.max_speed();
  n.accel = s.accel();
  n.waypoint_radius = s.waypoint_radius();
  n.arrive_distance = s.arrive_distance();
  n.separation_radius = s.separation_radius();
  n.separation_weight = s.separation_weight();
  n.gather_point = fromFb(s.gather_point());
  n.gather_radius = s.gather_radius();
  n.gather_start = s.gather_start();
  n.gather_end = s.gather_end();
  n.gathering = s.gathering();
  n.population = s.flock();
  decodeCrowd(s, n.crowd);
}

flatbuffers::Offset<fb::AvatarState> encodeAvatar(Builder& b, const AvatarData& a,
                                                  EntityKind kind) {
  if (kind != EntityKind::Avatar) return {};
  return fb::CreateAvatarState(b, a.player_id, a.last_input_seq, a.move_x, a.move_z, a.max_speed,
                               a.announced, a.kind, a.height, a.last_transaction_seq);
}

void decodeAvatar(const fb::AvatarState& s, AvatarData& a) {
  if (s.kind() >= kPlayerKindCount) throw CodecError("avatar record with unknown player kind");
  a = {s.player_id(), s.last_input_seq(), s.move_x(),  s.move_z(),
       s.max_speed(), s.announced(),      s.kind(),    s.height(),
       s.last_transaction_seq()};
}

flatbuffers::Offset<fb::ContactOrigin> encodeContactOrigin(Builder& b,
                                                           const CachedContactOrigin& o) {
  std::vector<fb::Vec3d> points;
  for (const Vec3& p : o.points) points.push_back(toFb(p));
  const auto points_at = b.CreateVectorOfStructs(points);
  const auto depths_at = b.CreateVector(o.depths);
  const fb::Vec3d normal = toFb(o.normal), first = toFb(o.first_position),
                  second = toFb(o.second_position);
  const fb::Quatd first_q = toFb(o.first_orientation), second_q = toFb(o.second_orientation);
  return fb::CreateContactOrigin(b, &normal, &first, &first_q, &second, &second_q, points_at,
                                 depths_at, o.friction, o.restitution, o.rolling);
}

CachedContactOrigin decodeContactOrigin(const fb::ContactOrigin& o, std::size_t points) {
  if (!o.normal() || !o.first_position() || !o.first_orientation() || !o.second_position() ||
      !o.second_orientation() || !o.points() || !o.depths())
    throw CodecError("cached contact origin with a missing field");
  if (o.points()->size() != points || o.depths()->size() != points)
    throw CodecError("cached contact origin with " + std::to_string(o.points()->size()) +
                     " points and " + std::to_string(o.depths()->size()) + " depths for a " +
                     std::to_string(points) + "-point contact");
  CachedContactOrigin out;
  out.normal = fromFb(o.normal());
  out.first_position = fromFb(o.first_position());
  out.first_orientation = fromFb(o.first_orientation());
  out.second_position = fromFb(o.second_position());
  out.second_orientation = fromFb(o.second_orientation());
  for (const fb::Vec3d* p : *o.points()) out.points.push_back(fromFb(p));
  out.depths.assign(o.depths()->begin(), o.depths()->end());
  out.friction = o.friction();
  out.restitution = o.restitution();
  out.rolling = o.rolling();
  return out;
}

flatbuffers::Offset<fb::BodyState> encodeBody(Builder& b, const BodyData& s, EntityKind kind) {
  if (kind != EntityKind::RigidBody) return {};
  flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<fb::CachedContact>>> contacts;
  if (!s.contacts.empty()) {
    std::vector<flatbuffers::Offset<fb::CachedContact>> list;
    std::vector<fb::CachedContactPoint> points;
    for (const CachedContact& c : s.contacts) {
      points.clear();
      for (const CachedContactPoint& p : c.points) {
        points.emplace_back(toFb(p.position), fb::Vec3d(p.impulse[0], p.impulse[1], p.impulse[2]),
                            p.feature);
      }
      const auto points_at = b.CreateVectorOfStructs(points);
      flatbuffers::Offset<fb::ContactOrigin> origin;
      if (c.origin) origin = encodeContactOrigin(b, *c.origin);
      list.push_back(fb::CreateCachedContact(b, c.other.value, c.world_body, c.piece_self,
                                             c.piece_other, points_at, c.rolling_impulse[0],
                                             c.rolling_impulse[1], origin));
    }
    contacts = b.CreateVector(list);
  }
  flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<fb::CachedJoint>>> joints;
  if (!s.joints.empty()) {
    std::vector<flatbuffers::Offset<fb::CachedJoint>> list;
    for (const CachedJoint& j : s.joints)
      list.push_back(fb::CreateCachedJoint(b, j.joint, b.CreateVector(j.impulses)));
    joints = b.CreateVector(list);
  }
  fb::Vec3d w = toFb(s.angular_velocity), h = toFb(s.half_extents);
  return fb::CreateBodyState(b, s.radius, s.mass, s.restitution, &w, s.sleeping, s.shape, &h,
                             s.half_height, s.friction, s.linear_damping, s.angular_damping,
                             s.rolling_resistance, s.rest_time, s.sleep_group.value, contacts,
                             joints, s.step_lag);
}

void decodeBody(const fb::BodyState& s, BodyData& d) {
  if (s.shape() > BodyData::Compound) throw CodecError("body record with unknown shape");
  if (s.step_lag() < 0)
    throw CodecError("body record with step lag " + std::to_string(s.step_lag()));
  d = {s.radius(),
       s.mass(),
       s.restitution(),
       fromFb(s.angular_velocity()),
       s.sleeping(),
       s.shape(),
       fromFb(s.half_extents()),
       s.half_height(),
       s.friction(),
       s.linear_damping(),
       s.angular_damping(),
       s.rolling_resistance(),
       s.rest_time(),
       EntityId{s.sleep_group()},
       {},
       {},
       s.step_lag()};
  if (s.joints()) {
    for (const fb::CachedJoint* j : *s.joints()) {
      if (j->joint() < 0) throw CodecError("cached joint without a joint index");
      CachedJoint out{j->joint(), {}};
      if (j->impulses()) out.impulses.assign(j->impulses()->begin(), j->impulses()->end());
      d.joints.push_back(std::move(out));
    }
  }
  if (!s.contacts()) return;
  for (const fb::CachedContact* c : *s.contacts()) {
    const std::size_t n = c->points() ? c->points()->size() : 0;
    if (n == 0 || n > 4) throw CodecError("cached contact with " + std::to_string(n) + " points");
    CachedContact out{EntityId{c->other()},
                      c->world_body(),
                      c->piece_self(),
                      c->piece_other(),
                      {},
                      {c->rolling_impulse_1(), c->rolling_impulse_2()},
                      std::nullopt};
    for (const fb::CachedContactPoint* p : *c->points()) {
      out.points.push_back({fromFb(&p->position()),
                            p->feature(),
                            {p->impulse().x(), p->impulse().y(), p->impulse().z()}});
    }
    if (c->origin()) out.origin = decodeContactOrigin(*c->origin(), n);
    d.contacts.push_back(std::move(out));
  }
}

flatbuffers::Offset<fb::EmitterState> encodeEmitter(Builder& b, const EmitterData& m,
                                                    EntityKind kind) {
  if (kind != EntityKind::Emitter) return {};
  return fb::CreateEmitterState(b, m.rate, m.lifetime, m.speed, m.spawn_accumulator, m.drag,
                                m.restitution, m.max_particles);
}

void decodeEmitter(const fb::EmitterState& s, EmitterData& m) {
  m = {s.rate(), s.lifetime(),    s.speed(),        s.spawn_accumulator(),
       s.drag(), s.restitution(), s.max_particles()};
}

flatbuffers::Offset<fb::AgentState> encodeAgent(Builder& b, const AgentData& a, EntityKind) {
  if (a.type < 0) return {};  // not an AI agent (of any kind)
  auto entered = b.CreateVector(a.entered, AgentData::kLevels);
  auto plan = b.CreateVector(a.plan, AgentData::kMaxPlan);
  auto path = b.CreateVector(a.path);
  return fb::CreateAgentState(b, a.type, a.state, a.step, entered, a.action, a.transitions,
                              a.health, a.energy, a.speed_factor, a.approach, a.facts, plan,
                              a.plan_length, a.plan_step, a.action_time, a.plan_cost, a.goal, a.nav,
                              a.dwell, a.origin_x, a.origin_z, a.target_x, a.target_z, a.travelled,
                              a.replans, a.arrivals, path, a.asked_tick, a.enemy_seen, a.enemy_x,
                              a.enemy_z, a.enemy_distance);
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
  a.enemy_seen = g.enemy_seen();
  a.enemy_x = g.enemy_x();
  a.enemy_z = g.enemy_z();
  a.enemy_distance = g.enemy_distance();
  a.path.clear();
  if (const auto* p = g.path()) a.path.assign(p->begin(), p->end());
  if (a.path.size() % 2 != 0) throw CodecError("agent record with an odd path");
}

flatbuffers::Offset<fb::CombatState> encodeCombat(Builder& b, const CombatData& c, EntityKind) {
  if (c == CombatData{}) return {};  // untouched: scenes without interactions carry nothing
  return fb::CreateCombatState(b, c.health, c.kills, c.deaths, c.items, c.mail_seq, c.taken_at);
}

void decodeCombat(const fb::CombatState& s, CombatData& c) {
  if (!(s.health() >= 0 && s.health() <= 100))
    throw CodecError("combat record with health outside 0..100");
  if (s.items() < 0) throw CodecError("combat record with negative items");
  c = {s.health(), s.kills(), s.deaths(), s.items(), s.mail_seq(), s.taken_at()};
}

// ---- One schema field per entity column (kEntityColumns) ----

/// How a column's value type is kept in one of EntityRecord's own fields.
template <typename T>
struct InlineValue;

template <>
struct InlineValue<EntityId> {
  static std::uint64_t encode(EntityId v) { return v.value; }
  static EntityId decode(std::uint64_t v) { return EntityId{v}; }
};
template <>
struct InlineValue<std::uint64_t> {
  static std::uint64_t encode(std::uint64_t v) { return v; }
  static std::uint64_t decode(std::uint64_t v) { return v; }
};
template <>
struct InlineValue<EntityKind> {
  static fb::EntityKind encode(EntityKind k) { return fb::EntityKind(k); }
  static EntityKind decode(fb::EntityKind k) {
    if (std::uint8_t(k) >= kEntityKindCount) throw CodecError("entity record with unknown kind");
    return EntityKind(k);
  }
};
template <>
struct InlineValue<Vec3> {
  static fb::Vec3d encode(const Vec3& v) { return toFb(v); }
  static Vec3 decode(const fb::Vec3d* v) { return fromFb(v); }
};
template <>
struct InlineValue<Quat> {
  static fb::Quatd encode(const Quat& q) { return toFb(q); }
  static Quat decode(const fb::Quatd* q) { return fromFb(q); }
};

/// A field whose tables and vectors are built, waiting for the record's table to be started
/// (FlatBuffers builds no table inside another). `size` is flatc's size class of the field: 8
/// for 64-bit scalars, 4 for offsets and structs, 1 for bytes.
template <typename Add>
struct PendingField {
  int size;
  Add add;  ///< void(RecordBuilder&)
};

/// A column kept in one of the record's own fields: `Add` and `Get` are the field's builder
/// setter and table getter; InlineValue of the column's type converts it.
template <auto Add, auto Get>
struct InlineField {
  template <typename T>
  static auto prepare(Builder&, const T& value, EntityKind) {
    auto v = InlineValue<T>::encode(value);
    constexpr bool is_struct = std::is_class_v<decltype(v)>;
    auto add = [v](RecordBuilder& rb) {
      if constexpr (is_struct) {
        (rb.*Add)(&v);
      } else {
        (rb.*Add)(v);
      }
    };
    return PendingField<decltype(add)>{is_struct ? 4 : int(sizeof(v)), add};
  }
  template <typename T>
  static void decode(const Record& e, T& value) {
    value = InlineValue<T>::decode((e.*Get)());
  }
};

/// A column kept in a table of its own: `Encode` builds it (a null offset where the entity has
/// none), `Decode` reads it where the record has one.
template <auto Add, auto Get, auto Encode, auto Decode>
struct TableField {
  template <typename T>
  static auto prepare(Builder& b, const T& value, EntityKind kind) {
    auto add = [table = Encode(b, value, kind)](RecordBuilder& rb) { (rb.*Add)(table); };
    return PendingField<decltype(add)>{4, add};
  }
  template <typename T>
  static void decode(const Record& e, T& value) {
    if (const auto* t = (e.*Get)()) Decode(*t, value);
  }
};

template <auto>
constexpr bool kNoSchemaField = false;

/// The schema field of the column whose record member is RecordMember.
template <auto RecordMember>
struct SchemaField {
  static_assert(kNoSchemaField<RecordMember>,
                "an entity column without a schema field: add its field at the end of "
                "EntityRecord in idl/entity_record.fbs and a SchemaField<&EntityRecordData::NAME> "
                "(an InlineField or a TableField) in zone_node/cluster/entity_codec.cpp");
};

// clang-format off
template <> struct SchemaField<&EntityRecordData::id> : InlineField<&RecordBuilder::add_id, &Record::id> {};
template <> struct SchemaField<&EntityRecordData::kind> : InlineField<&RecordBuilder::add_kind, &Record::kind> {};
template <> struct SchemaField<&EntityRecordData::pos> : InlineField<&RecordBuilder::add_pos, &Record::pos> {};
template <> struct SchemaField<&EntityRecordData::vel> : InlineField<&RecordBuilder::add_vel, &Record::vel> {};
template <> struct SchemaField<&EntityRecordData::rot> : InlineField<&RecordBuilder::add_rot, &Record::rot> {};
template <> struct SchemaField<&EntityRecordData::rng_state> : InlineField<&RecordBuilder::add_rng_state, &Record::rng_state> {};
template <> struct SchemaField<&EntityRecordData::npc> : TableField<&RecordBuilder::add_npc, &Record::npc, encodeNpc, decodeNpc> {};
template <> struct SchemaField<&EntityRecordData::avatar> : TableField<&RecordBuilder::add_avatar, &Record::avatar, encodeAvatar, decodeAvatar> {};
template <> struct SchemaField<&EntityRecordData::body> : TableField<&RecordBuilder::add_body, &Record::body, encodeBody, decodeBody> {};
template <> struct SchemaField<&EntityRecordData::emitter> : TableField<&RecordBuilder::add_emitter, &Record::emitter, encodeEmitter, decodeEmitter> {};
template <> struct SchemaField<&EntityRecordData::agent> : TableField<&RecordBuilder::add_agent, &Record::agent, encodeAgent, decodeAgent> {};
template <> struct SchemaField<&EntityRecordData::combat> : TableField<&RecordBuilder::add_combat, &Record::combat, encodeCombat, decodeCombat> {};
// clang-format on

/// The schema field of a column of kEntityColumns.
template <typename Column>
using FieldOf = SchemaField<std::remove_cvref_t<Column>::record>;

flatbuffers::Offset<Record> encodeEntity(Builder& b, const EntityRecordData& r) {
  // Component tables first (FlatBuffers cannot build them inside the open record), in column
  // order.
  auto pending = std::apply(
      [&](const auto&... c) {
        return std::tuple{FieldOf<decltype(c)>::prepare(b, r.*c.record, r.kind)...};
      },
      kEntityColumns);
  RecordBuilder rb(b);
  // The fields go in as flatc's own CreateEntityRecord adds them (widest first, the last declared
  // first): no padding between them, and the same bytes as flatc's builder, so checkpoints
  // written by code that used it still compare equal.
  constexpr std::size_t n = std::tuple_size_v<decltype(pending)>;
  auto add_sized = [&]<std::size_t... I>(int size, std::index_sequence<I...>) {
    auto add_if = [&](const auto& field) {
      if (field.size == size) field.add(rb);
    };
    (add_if(std::get<n - 1 - I>(pending)), ...);
  };
  for (int size : {8, 4, 2, 1}) add_sized(size, std::make_index_sequence<n>{});
  return rb.Finish();
}

EntityRecordData decodeEntity(const Record& e) {
  EntityRecordData r;
  forEachEntityColumn([&](const auto& c) { FieldOf<decltype(c)>::decode(e, r.*c.record); });
  if (!r.id) throw CodecError("entity record without id");
  return r;
}

}  // namespace

std::vector<std::uint8_t> encodeMigration(const MigrationPayload& p) {
  Builder b(256 + 256 * p.entities.size());
  std::vector<flatbuffers::Offset<Record>> entities;
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
    for (const Record* e : *es) p.entities.push_back(decodeEntity(*e));
  }
  if (const auto* ins = m->inputs()) {
    for (const fb::ForwardedInput* in : *ins)
      p.inputs.push_back({in->player_id(), in->seq(), in->move_x(), in->move_z()});
  }
  return p;
}

}  // namespace zonesim::zone
