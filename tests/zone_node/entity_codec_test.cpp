#include "zone_node/cluster/entity_codec.h"

#include <gtest/gtest.h>

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
  npc.npc.flock = 2;
  npc.npc.crowd_mode = 1;  // a rejoining formation member or a returning ant
  npc.npc.crowd_at = 3;
  npc.npc.crowd_x = 0.1;
  npc.npc.crowd_z = -7.25;
  npc.npc.crowd_path = {4, 5, 5, 6, 6, 6};
  npc.npc.crowd_seen = {9, 1};
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
  EXPECT_EQ(q.entities[0].npc.flock, 2);
  EXPECT_EQ(q.entities[0].npc.crowd_mode, 1);
  EXPECT_EQ(q.entities[0].npc.crowd_at, 3);
  EXPECT_EQ(q.entities[0].npc.crowd_x, 0.1);
  EXPECT_EQ(q.entities[0].npc.crowd_z, -7.25);
  EXPECT_EQ(q.entities[0].npc.crowd_path, npc.npc.crowd_path);
  EXPECT_EQ(q.entities[0].npc.crowd_seen, npc.npc.crowd_seen);
  EXPECT_EQ(q.entities[0].agent.type, 1);
  EXPECT_EQ(q.entities[0].agent.nav, 1);
  EXPECT_EQ(q.entities[0].agent.asked_tick, 123456789012ULL);
  EXPECT_EQ(q.entities[0].agent.travelled, 2.5);
  EXPECT_EQ(q.entities[0].agent.path, npc.agent.path);
  EXPECT_EQ(q.entities[1].npc.flock, -1);  // the default when absent from the record
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

}  // namespace
}  // namespace zonesim::zone
