// Avatars of the players' kinds: a new avatar gets its kind's top speed and, for a flyer, its
// height; a flyer holds that height at full speed, keeps its kind and height through a
// migration record and a checkpoint, and is nobody's neighbour on the ground below it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "common/scene.h"
#include "zone_node/avatar_spawn.h"
#include "zone_node/cluster/checkpoint.h"
#include "zone_node/cluster/entity_codec.h"
#include "zone_node/systems/avatar_movement.h"
#include "zone_node/systems/neighbourhood.h"

namespace zonesim::zone {
namespace {

constexpr std::uint8_t kWalker = 0, kRider = 1, kFlyer = 2;
constexpr double kFlyerSpeed = 30, kFlyerHeight = 80;

/// A 1 km world 100 m high (ground at y = 2) with walkers and flyers, no riders.
Scene kindsScene() {
  Scene s;
  s.world = {{0, 2, 0}, {1000, 102, 1000}};
  s.dt = 1.0 / 30;
  s.clients.kinds = {{PlayerKindId::Walker, 5, 100, 0, 0.9},
                     {PlayerKindId::Flyer, kFlyerSpeed, 300, kFlyerHeight, 0.1}};
  return s;
}

EntityStore storeWith(const EntityRecordData& r) {
  EntityStore store;
  store.add(r);
  return store;
}

double planarSpeed(const Vec3& v) {
  return std::hypot(v.x(), v.z());
}

TEST(NewAvatar, TakesItsKindsSpeedAndHeight) {
  Scene s = kindsScene();
  std::optional<EntityRecordData> flyer = newAvatar(s, 77, 500, 400, kFlyer);
  ASSERT_TRUE(flyer.has_value());
  EXPECT_EQ(flyer->kind, EntityKind::Avatar);
  EXPECT_EQ(flyer->avatar.player_id, 77u);
  EXPECT_EQ(flyer->avatar.kind, kFlyer);
  EXPECT_EQ(flyer->avatar.max_speed, kFlyerSpeed);
  EXPECT_EQ(flyer->avatar.height, kFlyerHeight);
  EXPECT_EQ(flyer->pos, Vec3(500, 2 + kFlyerHeight, 400));
  std::optional<EntityRecordData> walker = newAvatar(s, 78, 2000, -5, kWalker);
  ASSERT_TRUE(walker.has_value());
  EXPECT_EQ(walker->avatar.max_speed, 5);
  EXPECT_EQ(walker->avatar.height, 0);
  EXPECT_EQ(walker->pos.y(), 2) << "walkers stand on the ground";
  EXPECT_LT(walker->pos.x(), 1000) << "clamped into the world";
  EXPECT_EQ(walker->pos.z(), 0);
  EXPECT_FALSE(newAvatar(s, 79, 1, 1, kRider).has_value()) << "the scene has no riders";
  EXPECT_FALSE(newAvatar(s, 79, 1, 1, 200).has_value());
}

TEST(NewAvatar, ASceneWithoutKindsMakesTheWalkerOfBefore) {
  Scene s = kindsScene();
  s.clients.kinds.clear();
  s.clients.speed = 6;
  std::optional<EntityRecordData> a = newAvatar(s, 7, 10, 10, kWalker);
  ASSERT_TRUE(a.has_value());
  EXPECT_EQ(a->avatar.max_speed, 6);
  EXPECT_EQ(a->avatar.kind, kWalker);
  EXPECT_EQ(a->avatar.height, 0);
  EXPECT_EQ(a->pos.y(), 2);
  EXPECT_FALSE(newAvatar(s, 7, 10, 10, kFlyer).has_value());
}

// Steps the store's avatar `ticks` times toward (0.6, 0.8); expects it at the flyer's height,
// not moving vertically, after every step.
void flyAndCheckHeight(const Scene& s, EntityStore& store, int ticks) {
  store.avatar[0].move_x = 0.6f;
  store.avatar[0].move_z = 0.8f;
  for (int t = 0; t < ticks; ++t) {
    stepAvatars(s.world, store, s.dt);
    ASSERT_EQ(store.pos[0].y(), s.world.min.y + kFlyerHeight) << "tick " << t;
    ASSERT_EQ(store.vel[0].y(), 0) << "tick " << t;
  }
}

TEST(FlyerAvatar, HoldsItsHeightAtItsKindsSpeed) {
  Scene s = kindsScene();
  EntityRecordData r = *newAvatar(s, 9, 100, 100, kFlyer);
  r.id = EntityId::make(0, 1);
  r.vel = Vec3(0, -3, 0);  // whatever it had: a flyer does not sink
  EntityStore store = storeWith(r);
  flyAndCheckHeight(s, store, 90);  // 3 s: full speed after 1.25 s at kAvatarAccel
  // The input is floats: |(0.6f, 0.8f)| is 1 within float rounding.
  EXPECT_NEAR(planarSpeed(store.vel[0]), kFlyerSpeed, 1e-5);
  EXPECT_GT(store.pos[0].z(), 100 + 40) << "it moved on at the flyer's speed";
}

TEST(FlyerAvatar, KeepsKindHeightAndMotionAcrossAMigrationRecord) {
  Scene s = kindsScene();
  EntityRecordData r = *newAvatar(s, 9, 100, 100, kFlyer);
  r.id = EntityId::make(1, 3);
  EntityStore before = storeWith(r);
  flyAndCheckHeight(s, before, 30);
  MigrationPayload out;
  out.entities = {before.record(0)};
  MigrationPayload in = decodeMigration(encodeMigration(out));
  ASSERT_EQ(in.entities.size(), 1u);
  EXPECT_EQ(in.entities[0].avatar, before.avatar[0]);
  EXPECT_EQ(in.entities[0].avatar.kind, kFlyer);
  EXPECT_EQ(in.entities[0].avatar.height, kFlyerHeight);
  // The new owner steps it on exactly as the old one would have.
  EntityStore after = storeWith(in.entities[0]);
  flyAndCheckHeight(s, after, 60);
  flyAndCheckHeight(s, before, 60);
  EXPECT_EQ(after.pos[0], before.pos[0]);
  EXPECT_EQ(after.vel[0], before.vel[0]);
}

TEST(FlyerAvatar, KeepsItsKindThroughACheckpoint) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("zs_kind_ckpt_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  Scene s = kindsScene();
  EntityStore store;
  EntityRecordData flyer = *newAvatar(s, 9, 100, 100, kFlyer);
  flyer.id = EntityId::make(0, 1);
  EntityRecordData walker = *newAvatar(s, 10, 300, 100, kWalker);
  walker.id = EntityId::make(0, 2);
  store.add(flyer);
  store.add(walker);
  writeCheckpoint(MPI_COMM_WORLD, store, 30, 2, {}, dir.string());
  CheckpointImage image = readCheckpoint(dir.string());
  fs::remove_all(dir);
  ASSERT_EQ(image.entities.size(), 2u);
  for (const EntityRecordData& e : image.entities) {
    const bool is_flyer = e.id == flyer.id;
    EXPECT_EQ(e.avatar.kind, is_flyer ? kFlyer : kWalker);
    EXPECT_EQ(e.avatar.height, is_flyer ? kFlyerHeight : 0);
    EXPECT_EQ(e.avatar.max_speed, is_flyer ? kFlyerSpeed : 5);
    EXPECT_EQ(e.pos.y(), is_flyer ? 2 + kFlyerHeight : 2);
  }
}

TEST(FlyerAvatar, ARecordOfAnUnknownKindIsRefused) {
  EntityRecordData r;
  r.id = EntityId::make(0, 1);
  r.kind = EntityKind::Avatar;
  r.avatar.kind = std::uint8_t(kPlayerKindCount);
  MigrationPayload p;
  p.entities = {r};
  EXPECT_THROW(decodeMigration(encodeMigration(p)), CodecError);
}

TEST(FlyerAvatar, IsNobodysNeighbourOnTheGroundBelow) {
  Scene s = kindsScene();
  EntityStore store;
  EntityRecordData npc;
  npc.id = EntityId::make(0, 1);
  npc.kind = EntityKind::Npc;
  npc.pos = Vec3(100, 2, 100);
  store.add(npc);
  EntityRecordData flyer = *newAvatar(s, 9, 100.5, 100, kFlyer);
  flyer.id = EntityId::make(0, 2);
  store.add(flyer);
  EntityRecordData walker = *newAvatar(s, 10, 99.5, 100, kWalker);
  walker.id = EntityId::make(0, 3);
  store.add(walker);
  const double reach = 2;
  Neighbourhood near;
  near.build(store, nullptr, reach, s.world.min.y + reach);
  std::vector<Neighbour> found;
  near.query(npc.pos, reach, npc.id, found);
  ASSERT_EQ(found.size(), 1u) << "the walker beside the NPC, not the flyer above it";
  EXPECT_EQ(found[0].id, walker.id);
}

}  // namespace
}  // namespace zonesim::zone
