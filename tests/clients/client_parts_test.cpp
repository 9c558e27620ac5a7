// The client's pieces: dead reckoning of remote entities and the wander profile.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/remote_view.h"
#include "clients/reservoir.h"
#include "clients/wander.h"

namespace zonesim::clients {
namespace {

dr::WireEntity state(std::uint64_t id, std::uint64_t tick, double x, double z, double vx,
                     double vz) {
  dr::WireEntity e;
  e.id = id;
  e.tick = tick;
  e.state.pos = {x, 0, z};
  e.state.vel = {vx, 0, vz};
  return e;
}

constexpr double kDt = 0.1;  // simulated seconds per server tick in these tests

TEST(RemoteView, RunsTheEntitysModelFromItsSampleTick) {
  RemoteView v({false, 0.25, kDt});
  v.spawn(state(1, 10, 10, 20, 2, -1), 12);
  auto p = v.predicted(1, 30);  // 2 s after the sample
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->x, 14);
  EXPECT_DOUBLE_EQ(p->z, 18);
  EXPECT_FALSE(v.predicted(2, 30));
  // Second order: x = x0 + v t + a t^2 / 2.
  dr::WireEntity b = state(3, 0, 0, 0, 1, 0);
  b.model.order = dr::Order::Second;
  b.state.acc = {0.5, 0, 0};
  v.spawn(b, 0);
  EXPECT_DOUBLE_EQ(v.predicted(3, 20)->x, 1 * 2 + 0.5 * 4 / 2);
}

TEST(RemoteView, SnappingShowsTheNewModelAtOnce) {
  RemoteView v({false, 0.25, kDt});
  v.spawn(state(1, 0, 0, 0, 1, 0), 0);
  auto err = v.update(state(1, 10, 2, 0, 1, 0), 10);  // predicted x = 1, told x = 2
  ASSERT_TRUE(err);
  EXPECT_NEAR(*err, 1.0, 1e-9);
  EXPECT_NEAR(v.shown(1, 10)->x, 2, 1e-12);
  EXPECT_FALSE(v.update(state(1, 5, 0, 0, 0, 0), 10)) << "an older state never replaces a newer";
  EXPECT_FALSE(v.update(state(1, 10, 2, 0, 1, 0), 10)) << "a repeat of the held sample is ignored";
  EXPECT_FALSE(v.update(state(9, 10, 0, 0, 0, 0), 10)) << "unknown entities are not invented";
  EXPECT_EQ(v.size(), 1u);
  EXPECT_TRUE(v.despawn(1));
  EXPECT_FALSE(v.despawn(1));
  EXPECT_EQ(v.size(), 0u);
}

TEST(RemoteView, BlendingConvergesContinuouslyToTheNewModel) {
  RemoteView v({true, 0.5, kDt});
  v.spawn(state(1, 0, 0, 0, 1, 0), 0);
  v.update(state(1, 10, 2, 0, 1, 0), 10);  // a 1 m correction at tick 10
  // At the update the shown position has not jumped; it reaches the new model after 0.5 s
  // (5 ticks) and follows it from then on.
  EXPECT_NEAR(v.shown(1, 10)->x, 1, 1e-12);
  double prev = 1;
  for (double t = 10.5; t < 15; t += 0.5) {
    double x = v.shown(1, t)->x;
    // Same velocities: the 1 m gap closes linearly over 0.5 s on top of the 1 m/s walk, so
    // every 0.05 s the shown position moves 0.05 + 0.1 m, never a jump.
    EXPECT_NEAR(x - prev, 0.15, 1e-9);
    prev = x;
  }
  EXPECT_NEAR(v.shown(1, 15)->x, v.predicted(1, 15)->x, 1e-12);
  EXPECT_NEAR(v.shown(1, 20)->x, 3, 1e-12);
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
