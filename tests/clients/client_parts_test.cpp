// The client's pieces: dead reckoning of remote entities, the wander profile and the mix of
// player kinds.
#include <gtest/gtest.h>

#include <cmath>

#include "clients/kind_mix.h"
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

TEST(RemoteView, AFlyersCorrectionIsMeasuredInThreeDimensions) {
  // A flyer 60 m up, first at rest, then told it is a metre higher at the same place: the
  // error shown is that metre, not the zero a planar distance would give.
  RemoteView v({false, 0.25, 1.0 / 30});
  dr::WireEntity e = state(1, 10, 5, 5, 0, 0);
  e.state.pos.y = 60;
  v.spawn(e, 10);
  e.tick = 11;
  e.state.pos.y = 61;
  std::optional<double> err = v.update(e, 11);
  ASSERT_TRUE(err.has_value());
  EXPECT_NEAR(*err, 1.0, 1e-12);
  EXPECT_NEAR(v.shown(1, 11)->y, 61, 1e-12);
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

TEST(Wander, AFastKindArrivesFartherFromItsTarget) {
  SceneBox world{{0, 0, 0}, {1000, 10, 1000}};
  Wander walker(world, 8, 5, 1, 5), flyer(world, 8, 5, 1, 30);
  EXPECT_EQ(walker.arriveDistance(), Wander::kArriveDistance) << "walkers as before kinds";
  EXPECT_EQ(flyer.arriveDistance(), 30 * Wander::kArriveSeconds);
  walker.step(500, 500, 0);
  flyer.step(500, 500, 0);
  ASSERT_EQ(walker.targetX(), flyer.targetX()) << "the same stream";
  // 5 m short of the target: the flyer has arrived, the walker walks on.
  walker.step(walker.targetX() + 5, walker.targetZ(), 1);
  flyer.step(flyer.targetX() + 5, flyer.targetZ(), 1);
  EXPECT_EQ(walker.retargets(), 1u);
  EXPECT_EQ(flyer.retargets(), 2u);
}

TEST(KindMix, SharesBecomeExactCountsSpreadOverThePlayers) {
  std::vector<PlayerKind> kinds = {{PlayerKindId::Walker, 5, 100, 0, 0.7},
                                   {PlayerKindId::Rider, 12, 150, 0, 0.2},
                                   {PlayerKindId::Flyer, 30, 300, 80, 0.1}};
  EXPECT_EQ(kindCounts(kinds, 10), (std::vector<std::size_t>{7, 2, 1}));
  EXPECT_EQ(kindCounts(kinds, 100), (std::vector<std::size_t>{70, 20, 10}));
  EXPECT_EQ(kindCounts(kinds, 3), (std::vector<std::size_t>{2, 1, 0}));
  EXPECT_EQ(kindCounts(kinds, 0), (std::vector<std::size_t>{0, 0, 0}));
  EXPECT_TRUE(assignKinds({}, 5).empty()) << "no kinds to mix: the fleet's default kind";
  for (std::size_t n : {1u, 3u, 10u, 37u, 100u}) {
    std::vector<std::size_t> counts = kindCounts(kinds, n), given(3, 0);
    std::vector<PlayerKind> got = assignKinds(kinds, n);
    ASSERT_EQ(got.size(), n);
    for (std::size_t i = 0; i < n; ++i) {
      ++given[std::size_t(got[i].id)];
      // Every first i + 1 players are mixed within one player of the whole fleet's mix.
      for (std::size_t k = 0; k < 3; ++k)
        EXPECT_LT(std::fabs(double(given[k]) - double(i + 1) * double(counts[k]) / double(n)), 1.0)
            << n << " players, the first " << i + 1 << ", kind " << k;
    }
    EXPECT_EQ(given, counts) << n << " players";
  }
  // Not in blocks: riders and the flyer come between walkers, with their own settings.
  std::vector<PlayerKind> ten = assignKinds(kinds, 10);
  std::vector<PlayerKindId> ids;
  for (const PlayerKind& k : ten) ids.push_back(k.id);
  using enum PlayerKindId;
  EXPECT_EQ(ids, (std::vector<PlayerKindId>{Walker, Walker, Rider, Walker, Walker, Flyer, Walker,
                                            Walker, Rider, Walker}));
  EXPECT_EQ(ten[5].speed, 30);
  EXPECT_EQ(ten[5].height, 80);
}

TEST(KindMix, TheSceneKindsOrOneForcedKind) {
  ClientProfile plain;
  plain.speed = 4;
  std::vector<PlayerKind> one = fleetKinds(plain);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].id, PlayerKindId::Walker);
  EXPECT_EQ(one[0].speed, 4);
  EXPECT_EQ(fleetKinds(plain, "walker").size(), 1u);
  EXPECT_THROW(fleetKinds(plain, "flyer"), std::invalid_argument) << "no flyers in that scene";
  ClientProfile mixed;
  mixed.kinds = {{PlayerKindId::Walker, 5, 100, 0, 0.8}, {PlayerKindId::Flyer, 30, 300, 9, 0.2}};
  std::vector<PlayerKind> flyers = fleetKinds(mixed, "flyer");
  ASSERT_EQ(flyers.size(), 1u);
  EXPECT_EQ(flyers[0].id, PlayerKindId::Flyer);
  EXPECT_EQ(flyers[0].share, 1);
  EXPECT_EQ(flyers[0].height, 9);
  try {
    fleetKinds(mixed, "plane");
    ADD_FAILURE() << "accepted a kind the scene lacks";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "'plane' is not a kind of the scene (its kinds: walker, flyer)");
  }
}

TEST(Reservoir, KeepsTheLargestValueEvenWhenItIsNotSampled) {
  Reservoir r(4);
  EXPECT_EQ(r.max(), 0);
  for (int i = 0; i < 1000; ++i) r.add(i == 500 ? 99.0 : 1.0);
  EXPECT_EQ(r.max(), 99.0);
  Reservoir merged;
  merged.merge(r);
  EXPECT_EQ(merged.max(), 99.0);
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
