// The client's pieces: dead reckoning of remote entities and the wander profile.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/remote_view.h"
#include "clients/reservoir.h"
#include "clients/wander.h"

namespace zonesim::clients {
namespace {

proto::EntityState state(std::uint64_t id, float x, float z, float vx, float vz) {
  return proto::EntityState(id, 0, proto::Vec3f(x, 0, z), proto::Vec3f(vx, 0, vz),
                            proto::Quatf(0, 0, 0, 1));
}

constexpr std::int64_t kSecond = 1'000'000'000;

TEST(RemoteView, ExtrapolatesFirstOrderFromReceipt) {
  RemoteView v;
  v.spawn(state(1, 10, 20, 2, -1), kSecond);
  auto p = v.predicted(1, 3 * kSecond);
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->x, 14);
  EXPECT_DOUBLE_EQ(p->z, 18);
  EXPECT_FALSE(v.predicted(2, kSecond));
}

TEST(RemoteView, UpdateReportsTheCorrection) {
  RemoteView v;
  v.spawn(state(1, 0, 0, 1, 0), 0);
  auto err = v.update(state(1, 2, 0, 1, 0), kSecond);  // predicted x = 1, told x = 2
  ASSERT_TRUE(err);
  EXPECT_NEAR(*err, 1.0, 1e-9);
  EXPECT_FALSE(v.update(state(9, 0, 0, 0, 0), kSecond)) << "unknown entities are not invented";
  EXPECT_EQ(v.size(), 1u);
  EXPECT_TRUE(v.despawn(1));
  EXPECT_FALSE(v.despawn(1));
  EXPECT_EQ(v.size(), 0u);
}

TEST(Wander, WalksTowardTargetsInsideTheWorld) {
  SceneBox world{{-100, 0, 0}, {100, 10, 50}};
  Wander w(world, 8, 5, 0);
  Move m = w.step(0, 0, 0);
  EXPECT_NEAR(std::hypot(m.x, m.z), 1.0, 1e-5);
  double dx = w.targetX(), dz = w.targetZ();
  EXPECT_GE(dx, -100);
  EXPECT_LE(dx, 100);
  EXPECT_GE(dz, 0);
  EXPECT_LE(dz, 50);
  EXPECT_NEAR(m.x, dx / std::hypot(dx, dz), 1e-5);
}

TEST(Wander, RetargetsOnArrivalAndAfterTimeout) {
  SceneBox world{{0, 0, 0}, {100, 10, 100}};
  Wander w(world, 8, 5, 1);
  w.step(50, 50, 0);
  EXPECT_EQ(w.retargets(), 1u);
  w.step(w.targetX() + 0.5, w.targetZ(), 1);  // arrived
  EXPECT_EQ(w.retargets(), 2u);
  w.step(0, 0, 1 + 8);  // walked too long toward it
  EXPECT_EQ(w.retargets(), 3u);
}

TEST(Wander, EachPlayerHasItsOwnReproducibleStream) {
  SceneBox world{{0, 0, 0}, {100, 10, 100}};
  Wander a(world, 8, 5, 1), b(world, 8, 5, 1), c(world, 8, 5, 2);
  a.step(0, 0, 0);
  b.step(0, 0, 0);
  c.step(0, 0, 0);
  EXPECT_EQ(a.targetX(), b.targetX());
  EXPECT_NE(a.targetX(), c.targetX());
}

TEST(Reservoir, KeepsAllUntilFullThenStaysBounded) {
  Reservoir r(100, 1);
  for (int i = 0; i < 50; ++i) r.add(i);
  EXPECT_EQ(r.samples().size(), 50u);
  for (int i = 0; i < 100000; ++i) r.add(1000);
  EXPECT_EQ(r.samples().size(), 100u);
  EXPECT_EQ(r.seen(), 100050u);
}

}  // namespace
}  // namespace zonesim::clients
