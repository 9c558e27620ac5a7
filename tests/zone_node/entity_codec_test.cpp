#include "zone_node/cluster/entity_codec.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

namespace zonesim::zone {
namespace {

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
