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

}  // namespace
}  // namespace zonesim::zone
