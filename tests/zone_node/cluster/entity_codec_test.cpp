#include "zone_node/cluster/entity_codec.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace zonesim::zone {
namespace {

/// A record with every column away from its default, every component included.
EntityRecordData everyColumnSet() {
  EntityRecordData r;
  r.id = EntityId::make(7, 123456789);
  r.kind = EntityKind::Emitter;
  r.pos = Vec3(0.1, -0.2, 1.0 / 3.0);
  r.vel = Vec3(-1e-300, 5e300, 2.5);
  r.rot = Quat(0.5, -0.5, 0.5, 0.5);
  r.rng_state = 0xDEADBEEFCAFEBABEULL;
  r.npc = {.waypoint = Vec3(9, 1, 8),
           .max_speed = 1.75,
           .accel = 2.5,
           .waypoint_radius = 31,
           .arrive_distance = 1.5,
           .separation_radius = 0.7,
           .separation_weight = 2,
           .gather_point = Vec3(3, 0, 4),
           .gather_radius = 12,
           .gather_start = 100.5,
           .gather_end = 200.25,
           .gathering = true,
           .population = 4,
           .crowd = AntData{.mode = 1,
                            .route_at = 3,
                            .route_length = 0.1,
                            .route = {4, 5, 5, 6},
                            .dead_ends = {9, 1}}};
  r.avatar = {.player_id = 555,
              .last_input_seq = 41,
              .move_x = -0.5f,
              .move_z = 0.25f,
              .max_speed = 6.5,
              .announced = true,
              .kind = 2,
              .height = 80,
              .last_transaction_seq = 17};
  r.body = {
      .radius = 0.75,
      .mass = 3,
      .restitution = 0.6,
      .angular_velocity = Vec3(0.1, 0.2, 0.3),
      .sleeping = true,
      .shape = BodyData::Capsule,
      .half_extents = Vec3(1, 2, 3),
      .half_height = 0.9,
      .friction = 0.3,
      .linear_damping = 0.05,
      .angular_damping = 0.125,
      .rolling_resistance = 0.0625,
      .rest_time = 0.375,
      .sleep_group = EntityId::make(2, 77),
      .contacts = {{.other = EntityId::make(3, 9),
                    .piece_self = 1,
                    .piece_other = 2,
                    .points = {{Vec3(1, 2, 3), 0x10203, {0.5, -0.25, 0.125}},
                               {Vec3(-1, 0, 2), 7, {1.5, 0, -2}}},
                    .rolling_impulse = {0.01, -0.02},
                    .origin = CachedContactOrigin{.normal = Vec3(0, 0.6, 0.8),
                                                  .first_position = Vec3(1, 2.5, 3),
                                                  .second_position = Vec3(1, 3.5, 3.25),
                                                  .first_orientation = Quat(0.5, 0.5, 0.5, 0.5),
                                                  .second_orientation = Quat(0, 1, 0, 0),
                                                  .points = {Vec3(1, 3, 3), Vec3(-1, 0, 2)},
                                                  .depths = {0.004, -0.0125},
                                                  .friction = 0.4,
                                                  .restitution = 0.1,
                                                  .rolling = 0.03}},
                   {.other = EntityId{},
                    .world_body = 0,
                    .points = {{Vec3(4, 0, 5), 3, {9.81, 0, 0}}},
                    .origin = std::nullopt}},
      .joints = {{.joint = 2, .impulses = {0.5}},
                 {.joint = 0, .impulses = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}}},
      .step_lag = 3};
  r.emitter = {.rate = 250,
               .lifetime = 1.5,
               .speed = 7,
               .spawn_accumulator = 0.375,
               .drag = 0.2,
               .restitution = 0.6,
               .max_particles = 99};
  AgentData& a = r.agent;
  a.type = 2;
  a.state = 3;
  a.step = 40;
  for (int i = 0; i < AgentData::kLevels; ++i) a.entered[i] = 10 + i;
  a.action = 5;
  a.transitions = 6;
  a.health = 55.5;
  a.energy = 44.25;
  a.speed_factor = 0.8;
  a.approach = -0.4;
  a.facts = 0xF0F0;
  for (int i = 0; i < AgentData::kMaxPlan; ++i) a.plan[i] = i % 5;
  a.plan_length = 9;
  a.plan_step = 4;
  a.action_time = 1.25;
  a.plan_cost = 17.5;
  a.goal = 2;
  a.nav = 2;
  a.dwell = 0.5;
  a.origin_x = -3;
  a.origin_z = 4;
  a.target_x = 30;
  a.target_z = -40;
  a.travelled = 12.75;
  a.asked_tick = 123456789012ULL;
  a.replans = 3;
  a.arrivals = 8;
  a.path = {7, 8, 8, 9};
  a.enemy_seen = true;
  a.enemy_x = 12.5;
  a.enemy_z = -6.25;
  a.enemy_distance = 3.75;
  r.combat = {.health = 37.5,
              .kills = 3,
              .deaths = 2,
              .items = 7,
              .mail_seq = 99,
              .taken_at = 12345678901ull};
  return r;
}

/// What a record of its kind arrives as: each kind carries its own component only.
EntityRecordData carried(EntityRecordData r) {
  if (r.kind != EntityKind::Npc) r.npc = {};
  if (r.kind != EntityKind::Avatar) r.avatar = {};
  if (r.kind != EntityKind::RigidBody) r.body = {};
  if (r.kind != EntityKind::Emitter) r.emitter = {};
  return r;
}

template <typename T>
bool same(const T& a, const T& b) {
  return a == b;
}
bool same(const Quat& a, const Quat& b) {
  return a.coeffs() == b.coeffs();
}

// Driven by kEntityColumns, so a new column is checked as soon as it is listed: it must be set
// in everyColumnSet() and must come back from its schema field unchanged.
TEST(EntityCodec, EveryColumnRoundTripsForEveryKind) {
  const EntityRecordData full = everyColumnSet();
  const EntityRecordData defaults;
  forEachEntityColumn([&](const auto& c) {
    EXPECT_FALSE(same(full.*c.record, defaults.*c.record))
        << c.name << " is at its default: set it in everyColumnSet()";
  });
  MigrationPayload p;
  for (int k = 0; k < kEntityKindCount; ++k) {
    EntityRecordData r = full;
    r.kind = EntityKind(k);
    r.id = EntityId::make(7, std::uint64_t(k) + 1);
    p.entities.push_back(r);
  }
  MigrationPayload q = decodeMigration(encodeMigration(p));
  ASSERT_EQ(q.entities.size(), p.entities.size());
  for (std::size_t i = 0; i < p.entities.size(); ++i) {
    const EntityRecordData want = carried(p.entities[i]);
    int columns = 0;
    forEachEntityColumn([&](const auto& c) {
      ++columns;
      EXPECT_TRUE(same(q.entities[i].*c.record, want.*c.record))
          << c.name << " of a record of kind " << int(want.kind);
    });
    EXPECT_EQ(columns, int(std::tuple_size_v<decltype(kEntityColumns)>));
  }
}

// Every prefix of a batch is refused: the Verifier finds what is cut off, wherever the cut.
TEST(EntityCodec, EveryTruncationIsRefused) {
  MigrationPayload p;
  p.entities = {everyColumnSet()};
  p.entities[0].kind = EntityKind::Npc;
  p.inputs = {{555, 42, 1.0f, 0.0f}};
  const std::vector<std::uint8_t> bytes = encodeMigration(p);
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::vector<std::uint8_t> prefix(bytes.begin(), bytes.begin() + long(n));
    EXPECT_THROW(decodeMigration(prefix), CodecError) << n << " of " << bytes.size() << " bytes";
  }
}

// Values that pass the Verifier (it checks structure only) but no entity can hold are refused,
// each with the reason.
TEST(EntityCodec, OutOfRangeValuesAreRefusedWithTheirReason) {
  struct Case {
    const char* reason;
    void (*spoil)(EntityRecordData&);
  };
  const Case cases[] = {
      {"entity record with unknown kind", [](EntityRecordData& r) { r.kind = EntityKind(9); }},
      {"entity record without id", [](EntityRecordData& r) { r.id = EntityId{}; }},
      {"body record with unknown shape",
       [](EntityRecordData& r) {
         r.kind = EntityKind::RigidBody;
         r.body.shape = BodyData::Compound + 1;
       }},
      {"cached contact with 0 points",
       [](EntityRecordData& r) {
         r.kind = EntityKind::RigidBody;
         r.body.contacts[0].points.clear();
       }},
      {"cached contact with 5 points",
       [](EntityRecordData& r) {
         r.kind = EntityKind::RigidBody;
         r.body.contacts[1].points.assign(5, CachedContactPoint{});
       }},
      {"cached contact origin with 1 points and 2 depths for a 2-point contact",
       [](EntityRecordData& r) {
         r.kind = EntityKind::RigidBody;
         r.body.contacts[0].origin->points.pop_back();
       }},
      {"body record with step lag -2",
       [](EntityRecordData& r) {
         r.kind = EntityKind::RigidBody;
         r.body.step_lag = -2;
       }},
      {"cached joint without a joint index",
       [](EntityRecordData& r) {
         r.kind = EntityKind::RigidBody;
         r.body.joints[0].joint = -1;
       }},
      {"npc record with an odd cell list",
       [](EntityRecordData& r) {
         r.npc.crowd = FormationMemberData{0, 0, 0, 0, {1, 2, 3}};
       }},
      {"agent record with an odd path",
       [](EntityRecordData& r) {
         r.agent.path = {1, 2, 3};
       }},
      {"agent record with a long plan",
       [](EntityRecordData& r) { r.agent.plan_length = AgentData::kMaxPlan + 1; }},
      {"combat record with health outside 0..100",
       [](EntityRecordData& r) { r.combat.health = 101; }},
      {"combat record with negative items", [](EntityRecordData& r) { r.combat.items = -1; }},
  };
  for (const Case& c : cases) {
    MigrationPayload p;
    p.entities = {everyColumnSet()};
    p.entities[0].kind = EntityKind::Npc;
    c.spoil(p.entities[0]);
    try {
      decodeMigration(encodeMigration(p));
      ADD_FAILURE() << "accepted a record meant to fail with: " << c.reason;
    } catch (const CodecError& e) {
      EXPECT_EQ(std::string(e.what()), c.reason);
    }
  }
}

TEST(EntityCodec, MigrationBatchRoundTripsBitForBit) {
  MigrationPayload p;
  p.tick = 77;
  p.from_rank = 3;
  EntityRecordData npc;
  npc.id = EntityId::make(0xFFFF, 12);
  npc.kind = EntityKind::Npc;
  npc.pos = Vec3(0.1, 0.2, 1.0 / 3.0);
  npc.vel = Vec3(-1e-300, 5e300, 2.5);
  npc.rot = Quat(0.5, 0.5, 0.5, 0.5);
  npc.rng_state = 0xDEADBEEFCAFEBABEULL;
  npc.npc.waypoint = Vec3(9, 0, 8);
  npc.npc.max_speed = 1.75;
  npc.npc.population = 2;
  npc.npc.crowd = AntData{1, 3, 0.1, {4, 5, 5, 6, 6, 6}, {9, 1}};  // a returning ant
  npc.agent.type = 1;  // an agent whose path request waits in the cluster's queue
  npc.agent.nav = 1;
  npc.agent.asked_tick = 123456789012ULL;
  npc.agent.travelled = 2.5;
  npc.agent.path = {7, 8};
  EntityRecordData avatar;
  avatar.id = EntityId::make(2, 1);
  avatar.kind = EntityKind::Avatar;
  avatar.avatar.player_id = 555;
  avatar.avatar.last_input_seq = 41;
  avatar.avatar.move_x = -0.5f;
  avatar.avatar.last_transaction_seq = 17;
  p.entities = {npc, avatar};
  p.inputs = {{555, 42, 1.0f, 0.0f}};

  MigrationPayload q = decodeMigration(encodeMigration(p));
  EXPECT_EQ(q.tick, 77u);
  EXPECT_EQ(q.from_rank, 3);
  ASSERT_EQ(q.entities.size(), 2u);
  EXPECT_EQ(q.entities[0].id, npc.id);
  EXPECT_EQ(q.entities[0].pos, npc.pos);
  EXPECT_EQ(q.entities[0].vel, npc.vel);
  EXPECT_EQ(q.entities[0].rot.coeffs(), npc.rot.coeffs());
  EXPECT_EQ(q.entities[0].rng_state, npc.rng_state);
  EXPECT_EQ(q.entities[0].npc.waypoint, npc.npc.waypoint);
  EXPECT_EQ(q.entities[0].npc.max_speed, 1.75);
  EXPECT_EQ(q.entities[0].npc.population, 2);
  const auto* ant = std::get_if<AntData>(&q.entities[0].npc.crowd);
  ASSERT_NE(ant, nullptr);
  EXPECT_EQ(ant->mode, 1);
  EXPECT_EQ(ant->route_at, 3);
  EXPECT_EQ(ant->route_length, 0.1);
  EXPECT_EQ(ant->route, (std::vector<std::int32_t>{4, 5, 5, 6, 6, 6}));
  EXPECT_EQ(ant->dead_ends, (std::vector<std::int32_t>{9, 1}));
  EXPECT_EQ(q.entities[0].agent.type, 1);
  EXPECT_EQ(q.entities[0].agent.nav, 1);
  EXPECT_EQ(q.entities[0].agent.asked_tick, 123456789012ULL);
  EXPECT_EQ(q.entities[0].agent.travelled, 2.5);
  EXPECT_EQ(q.entities[0].agent.path, npc.agent.path);
  EXPECT_EQ(q.entities[1].npc.population, -1);  // the default when absent from the record
  EXPECT_EQ(q.entities[1].kind, EntityKind::Avatar);
  EXPECT_EQ(q.entities[1].avatar.player_id, 555u);
  EXPECT_EQ(q.entities[1].avatar.last_input_seq, 41u);
  EXPECT_EQ(q.entities[1].avatar.move_x, -0.5f);
  EXPECT_EQ(q.entities[1].avatar.last_transaction_seq, 17u) << "the next owner goes on from it";
  ASSERT_EQ(q.inputs.size(), 1u);
  EXPECT_EQ(q.inputs[0].seq, 42u);
}

TEST(EntityCodec, CorruptBuffersAreRejected) {
  MigrationPayload p;
  EntityRecordData e;
  e.id = EntityId::make(1, 1);
  p.entities = {e};
  std::vector<std::uint8_t> bytes = encodeMigration(p);
  std::vector<std::uint8_t> truncated(bytes.begin(), bytes.begin() + long(bytes.size() / 2));
  EXPECT_THROW(decodeMigration(truncated), CodecError);
  std::vector<std::uint8_t> wrong_id = bytes;
  wrong_id[4] ^= 0xFF;  // file identifier "ZSER" lives at bytes 4..7
  EXPECT_THROW(decodeMigration(wrong_id), CodecError);
  std::vector<std::uint8_t> garbage(64, 0xAB);
  EXPECT_THROW(decodeMigration(garbage), CodecError);
}

// A segment of a gathered buffer may start at any byte. Reading its Vec3d in place there is
// undefined (an -fsanitize=undefined build stops on it); the decoder must give the same records.
TEST(EntityCodec, BatchAtAMisalignedAddressDecodesTheSame) {
  MigrationPayload p;
  EntityRecordData e;
  e.id = EntityId::make(4, 9);
  e.kind = EntityKind::RigidBody;
  e.pos = Vec3(1.5, -2.25, 1.0 / 7.0);
  e.body.angular_velocity = Vec3(0.1, 0.2, 0.3);
  e.body.linear_damping = 0.5;
  e.body.angular_damping = 0.25;
  e.body.rolling_resistance = 0.04;
  p.entities = {e};
  std::vector<std::uint8_t> bytes = encodeMigration(p);
  std::vector<std::uint8_t> storage(bytes.size() + kBatchAlign);
  std::uint8_t* at = storage.data() + 1;  // storage itself is aligned by operator new
  ASSERT_NE(reinterpret_cast<std::uintptr_t>(at) % kBatchAlign, 0u);
  std::memcpy(at, bytes.data(), bytes.size());

  MigrationPayload q = decodeMigration(std::span<const std::uint8_t>(at, bytes.size()));
  ASSERT_EQ(q.entities.size(), 1u);
  EXPECT_EQ(q.entities[0].id, e.id);
  EXPECT_EQ(q.entities[0].pos, e.pos);
  EXPECT_EQ(q.entities[0].body.angular_velocity, e.body.angular_velocity);
  EXPECT_EQ(q.entities[0].body.linear_damping, 0.5);  // a damped body stays damped on arrival
  EXPECT_EQ(q.entities[0].body.angular_damping, 0.25);
  EXPECT_EQ(q.entities[0].body.rolling_resistance, 0.04);  // and still slows as it rolls
}

TEST(EntityCodec, EveryKindOfCrowdStateMigratesAsItsOwnType) {
  const std::vector<CrowdState> states{std::monostate{},
                                       FormationMemberData{2, 1, 4.5, -3.25, {1, 2, 2, 3}},
                                       AntData{1, 0, 12.5, {0, 0, 1, 1}, {}}, RoadTripData{7, 9}};
  MigrationPayload p;
  for (std::size_t k = 0; k < states.size(); ++k) {
    EntityRecordData r;
    r.id = EntityId::make(1, k + 1);
    r.kind = EntityKind::Npc;
    r.npc.population = std::int32_t(k) - 1;
    r.npc.crowd = states[k];
    p.entities.push_back(r);
  }
  MigrationPayload q = decodeMigration(encodeMigration(p));
  ASSERT_EQ(q.entities.size(), states.size());
  for (std::size_t k = 0; k < states.size(); ++k) {
    EXPECT_EQ(q.entities[k].npc.crowd.index(), states[k].index()) << k;
    EXPECT_EQ(q.entities[k].npc.population, std::int32_t(k) - 1);
  }
  const auto& m = std::get<FormationMemberData>(q.entities[1].npc.crowd);
  EXPECT_EQ(m.mode, 2);
  EXPECT_EQ(m.path_at, 1);
  EXPECT_EQ(m.planned_x, 4.5);
  EXPECT_EQ(m.planned_z, -3.25);
  EXPECT_EQ(m.path, (std::vector<std::int32_t>{1, 2, 2, 3}));
  const auto& trip = std::get<RoadTripData>(q.entities[3].npc.crowd);
  EXPECT_EQ(trip.next_node, 7);
  EXPECT_EQ(trip.goal, 9);
}

}  // namespace
}  // namespace zonesim::zone
