#include "zone_node/entity_store.h"

#include <gtest/gtest.h>

namespace zonesim::zone {
namespace {

EntityRecordData make(std::uint64_t counter, EntityKind kind, std::uint64_t player = 0) {
  EntityRecordData r;
  r.id = EntityId::make(1, counter);
  r.kind = kind;
  r.pos = Vec3(double(counter), 0, 0);
  r.avatar.player_id = player;
  return r;
}

TEST(EntityStore, LookupsStayCorrectAcrossSwapRemovals) {
  EntityStore s;
  for (std::uint64_t i = 1; i <= 10; ++i)
    s.add(make(i, i % 3 == 0 ? EntityKind::Avatar : EntityKind::Npc, 100 + i));
  EXPECT_EQ(s.count(EntityKind::Avatar), 3u);
  s.removeAt(*s.indexOf(EntityId::make(1, 2)));
  s.removeAt(*s.indexOf(EntityId::make(1, 3)));  // an avatar
  s.removeAt(0);                                 // entity 1
  EXPECT_EQ(s.size(), 7u);
  EXPECT_EQ(s.count(EntityKind::Avatar), 2u);
  EXPECT_FALSE(s.indexOf(EntityId::make(1, 2)));
  EXPECT_FALSE(s.avatarOf(103));
  for (std::uint64_t i = 4; i <= 10; ++i) {
    auto idx = s.indexOf(EntityId::make(1, i));
    ASSERT_TRUE(idx) << i;
    EXPECT_EQ(s.pos[*idx].x(), double(i));  // components moved together with the id
  }
  ASSERT_TRUE(s.avatarOf(106));
  EXPECT_EQ(s.id[*s.avatarOf(106)], EntityId::make(1, 6));
}

TEST(EntityStore, RecordRoundTripsEveryComponent) {
  EntityStore s;
  EntityRecordData r = make(5, EntityKind::RigidBody);
  r.vel = Vec3(1, 2, 3);
  r.body.radius = 0.25;
  r.rng_state = 42;
  s.add(r);
  EntityRecordData back = s.record(0);
  EXPECT_EQ(back.id, r.id);
  EXPECT_EQ(back.vel, r.vel);
  EXPECT_EQ(back.body.radius, 0.25);
  EXPECT_EQ(back.rng_state, 42u);
}

TEST(EntityStore, EveryColumnOfTheListIsStoredMovedOnRemovalAndCopiedOut) {
  // Two entities whose every component differs: removing the first moves the second into its
  // place column by column, and its record comes back whole.
  EntityStore s;
  EntityRecordData a = make(1, EntityKind::Npc), b = make(2, EntityKind::Avatar);
  b.pos = Vec3(1, 2, 3);
  b.vel = Vec3(4, 5, 6);
  b.rot = Quat(0, 1, 0, 0);
  b.rng_state = 77;
  b.npc.max_speed = 3.5;
  b.npc.crowd = AntData{1, 2, 3.5, {1, 2, 3, 4}, {5, 6}};
  b.avatar.player_id = 9;
  b.body.mass = 7;
  b.emitter.rate = 11;
  b.agent.type = 2;
  b.agent.path = {5, 6};
  s.add(a);
  s.add(b);
  s.removeAt(0);
  ASSERT_EQ(s.size(), 1u);
  std::size_t columns = 0;
  forEachEntityColumn([&](const auto& c) {
    ++columns;
    EXPECT_EQ((s.*c.store).size(), 1u) << c.name;
  });
  EXPECT_EQ(columns, std::tuple_size_v<decltype(kEntityColumns)>);
  EntityRecordData back = s.record(0);
  EXPECT_EQ(back.id, b.id);
  EXPECT_EQ(back.kind, EntityKind::Avatar);
  EXPECT_EQ(back.pos, b.pos);
  EXPECT_EQ(back.vel, b.vel);
  EXPECT_EQ(back.rot.coeffs(), b.rot.coeffs());
  EXPECT_EQ(back.rng_state, 77u);
  EXPECT_EQ(back.npc.max_speed, 3.5);
  EXPECT_EQ(std::get<AntData>(back.npc.crowd).dead_ends, std::get<AntData>(b.npc.crowd).dead_ends);
  EXPECT_EQ(back.avatar.player_id, 9u);
  EXPECT_EQ(back.body.mass, 7.0);
  EXPECT_EQ(back.emitter.rate, 11.0);
  EXPECT_EQ(back.agent.type, 2);
  EXPECT_EQ(back.agent.path, b.agent.path);
  EXPECT_EQ(s.avatarOf(9), std::optional<std::size_t>(0));
}

}  // namespace
}  // namespace zonesim::zone
