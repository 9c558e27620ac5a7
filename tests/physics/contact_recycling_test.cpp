// Contact recycling: a carried manifold moves with its bodies, the motion bound is what the
// geometry says, and a world that recycles finds exactly the touching pairs (so every contact
// begins and ends) that the narrowphase finds from the same state.
#include "physics/contact_recycling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>
#include <span>
#include <utility>
#include <vector>

#include "physics/box_column.h"
#include "physics/world.h"

namespace zonesim::physics {
namespace {

constexpr double kDt = 1.0 / 60.0;

Quat turnAboutY(double angle) {
  return Quat(Eigen::AngleAxisd(angle, Vec3::UnitY()));
}

TEST(ContactRecycling, BoundingRadiusIsTheFarthestPoint) {
  EXPECT_DOUBLE_EQ(boundingRadius(Shape::box(Vec3(1, 2, 2))), 3.0);
  EXPECT_DOUBLE_EQ(boundingRadius(Shape::sphere(0.4)), std::sqrt(3 * 0.16));  // its bounds' corner
  EXPECT_TRUE(std::isinf(boundingRadius(Shape::plane())));
}

TEST(ContactRecycling, MotionBoundOfATranslationIsItsLength) {
  ManifoldOrigin then;
  then.a = Pose{Vec3(0, 0, 0), Quat::Identity()};
  then.b = Pose{Vec3(0, 1, 0), Quat::Identity()};
  const Pose a = then.a, b{Vec3(0.003, 1.004, 0), Quat::Identity()};
  EXPECT_NEAR(relativeMotionBound(then, a, b, 1.0, 1.0, 1.0), 0.005, 1e-15);
  // Both bodies carried along together: no relative motion at all.
  const Pose a2{Vec3(2, 3, 4), turnAboutY(0.1)},
      b2{a2.position + a2.orientation * Vec3(0, 1, 0), a2.orientation};
  EXPECT_NEAR(relativeMotionBound(then, a2, b2, 1.0, 1.0, 1.0), 0.0, 1e-15);
}

TEST(ContactRecycling, MotionBoundOfATurnIsTheChordAtTheSmallerRadius) {
  ManifoldOrigin then;
  then.a = Pose{Vec3(0, 0, 0), Quat::Identity()};
  then.b = Pose{Vec3(0, 1, 0), Quat::Identity()};
  const double angle = 0.02;
  const Pose b{then.b.position, turnAboutY(angle)};
  const double chord = 2 * std::sin(angle / 2);
  // b turned about its own origin: its points moved by at most its radius times the chord.
  EXPECT_NEAR(relativeMotionBound(then, then.a, b, 100.0, 0.5, 0.0), 0.5 * chord, 1e-15);
  // Seen from b, a's origin swung round b's, which also counts: the smaller bound wins.
  EXPECT_LE(relativeMotionBound(then, then.a, b, 0.5, 0.5, 0.0), 0.5 * chord + 1e-15);
}

TEST(ContactRecycling, CarriedPointsMoveWithBothBodies) {
  Manifold m;
  m.normal = Vec3::UnitY();
  m.add(Vec3(0.5, 0.0, 0.5), 0.01, 1);
  m.add(Vec3(-0.5, 0.0, -0.5), 0.02, 2);
  const Pose a{Vec3(0, -1, 0), Quat::Identity()}, b{Vec3(0, 0.5, 0), Quat::Identity()};
  const ManifoldOrigin o = originOf(m, a, b);
  // b rises 3 mm and slides 1 cm along x: the gap grows by 3 mm, the points slide half as far.
  const Pose b2{b.position + Vec3(0.01, 0.003, 0), b.orientation};
  Manifold out = m;
  carryManifold(o, m.normal, m.count, a, b2, out);
  EXPECT_NEAR(out.points[0].depth, 0.007, 1e-15);
  EXPECT_NEAR(out.points[1].depth, 0.017, 1e-15);
  EXPECT_NEAR((out.points[0].position - Vec3(0.505, 0.0015, 0.5)).norm(), 0.0, 1e-15);
  EXPECT_EQ(out.points[1].feature, 2u);
  // The pair turned as a whole past the kept normal's limit: not to be recycled.
  EXPECT_TRUE(turnedLittle(o, a, b2, 0.98));
  EXPECT_FALSE(turnedLittle(o, a, Pose{b.position, turnAboutY(0.25)}, 0.98));
}

TEST(ContactRecycling, CarriedPointsAreSortedDeepestFirstWithTheirOriginsAndImpulses) {
  Manifold m;
  m.add(Vec3(1, 0, 0), 0.01, 1);
  m.add(Vec3(2, 0, 0), 0.03, 2);
  m.add(Vec3(3, 0, 0), 0.01, 3);
  m.add(Vec3(4, 0, 0), 0.02, 4);
  ManifoldOrigin o = originOf(m, Pose{}, Pose{});
  std::array<std::array<double, 3>, 4> impulse{};
  for (int i = 0; i < 4; ++i) impulse[i] = {double(i + 1), 0, 0};
  sortDeepestFirst(m, o, impulse);
  const std::uint32_t order[] = {2, 4, 1, 3};  // equal depths keep their order
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(m.points[i].feature, order[i]);
    EXPECT_EQ(o.point[i], m.points[i].position);
    EXPECT_EQ(o.depth[i], m.points[i].depth);
    EXPECT_EQ(impulse[i][0], double(order[i]));
  }
}

// The solvers visit a manifold's points in order, the first taking the most load. Carried points
// that kept the order they were found in let a 20-box column rock and walk 3.7 cm (soft step)
// and 3.4 cm (wide) in 60 s; sorted, it stands as still as without recycling.
TEST(ContactRecycling, ARecycledColumnStandsAsStillAsAComputedOne) {
  const std::vector<double> densities(20, 1000.0);
  for (SolverKind kind : {SolverKind::SoftStep, SolverKind::SoftStepWide}) {
    double drift[2] = {0, 0};
    for (int recycling = 0; recycling < 2; ++recycling) {
      WorldSettings settings;
      settings.solver.kind = kind;
      settings.solver.velocity_iterations = 20;
      settings.solver.position_iterations = 1;
      settings.contact_recycle_distance = recycling ? 0.01 : 0.0;
      BoxColumn column(settings, densities);
      column.run(60);
      drift[recycling] = column.drift().horizontal;
      if (recycling) {
        EXPECT_GT(column.world().recycledContacts(), 0u);
      }
    }
    std::printf(
        "%s: 20-box column's largest sideways drift in 60 s: %.2e m computed, %.2e m "
        "recycled at 0.01 m\n",
        kind == SolverKind::SoftStep ? "soft step" : "wide soft step", drift[0], drift[1]);
    EXPECT_LT(drift[1], 1e-3);
    EXPECT_LT(drift[1], 2 * drift[0] + 1e-4);
  }
}

/// A floor plane, a static platform, and boxes and spheres dropped onto both and each other
/// with random spins: pairs begin and end touching all through the run.
std::vector<BodyDesc> tumblingPile() {
  std::vector<BodyDesc> out;
  BodyDesc floor;
  floor.type = BodyType::Static;
  floor.shape = Shape::plane();
  out.push_back(floor);
  BodyDesc platform;
  platform.type = BodyType::Static;
  platform.shape = Shape::box(Vec3(2, 0.5, 2));
  platform.position = Vec3(1, 0.5, 0);
  out.push_back(platform);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 48; ++k) {
    BodyDesc d;
    d.shape = k % 3 == 0 ? Shape::sphere(0.3) : Shape::box(Vec3(0.4, 0.25, 0.3));
    d.position = Vec3(2.5 * u(rng), 1.5 + 0.6 * k, 2.0 * u(rng));
    d.orientation =
        Quat(Eigen::AngleAxisd(u(rng) * std::numbers::pi, Vec3(u(rng), 1, u(rng)).normalized()));
    d.linear_velocity = Vec3(u(rng), 0, u(rng));
    d.angular_velocity = Vec3(u(rng), u(rng), u(rng)) * 2.0;
    d.friction = 0.5;
    out.push_back(d);
  }
  return out;
}

std::set<std::pair<BodyIndex, BodyIndex>> pairsOf(const World& w) {
  std::set<std::pair<BodyIndex, BodyIndex>> out;
  for (const BodyContact& c : w.contacts()) out.emplace(c.a, c.b);
  return out;
}

/// Steps the pile with recycling, and at every step the same state without it: both must find
/// the same touching pairs, and the events must be their changes.
void expectExactPairs(WorldSettings settings) {
  settings.contact_events = true;
  WorldSettings fresh_settings = settings;
  settings.contact_recycle_distance = 0.01;
  World recycling(settings), fresh(fresh_settings);
  for (const BodyDesc& d : tumblingPile()) {
    recycling.addBody(d);
    fresh.addBody(d);
  }
  std::size_t recycled = 0, computed = 0, begun = 0, ended = 0;
  double worst_depth_gap = 0.0;
  std::set<std::pair<BodyIndex, BodyIndex>> before;
  WarmStarts warm;
  for (int step = 0; step < 600; ++step) {
    // The same state stepped without recycling finds the pairs the narrowphase finds.
    fresh.bodies() = recycling.bodies();
    for (BodyIndex i = 0; i < recycling.bodies().size(); ++i)
      fresh.setSleepState(i, recycling.sleepState(i));
    recycling.warmStarts(warm);
    fresh.setWarmStarts(warm);
    recycling.step(kDt);
    fresh.step(kDt);
    const auto pairs = pairsOf(recycling);
    ASSERT_EQ(pairs, pairsOf(fresh)) << "step " << step;
    recycled += recycling.recycledContacts();
    computed += recycling.computedContacts();
    // The events are the changes of the touching pairs, awake or asleep.
    recycling.warmStarts(warm);
    std::set<std::pair<BodyIndex, BodyIndex>> touching, began, stopped;
    for (const BodyContact& c : warm.contacts) touching.emplace(c.a, c.b);
    for (const auto& p : touching)
      if (!before.count(p)) began.insert(p);
    for (const auto& p : before)
      if (!touching.count(p)) stopped.insert(p);
    const ContactEvents& events = recycling.contactEvents();
    ASSERT_EQ(began, std::set(events.begun().begin(), events.begun().end())) << "step " << step;
    ASSERT_EQ(stopped, std::set(events.ended().begin(), events.ended().end())) << "step " << step;
    begun += began.size();
    ended += stopped.size();
    before = touching;
    // A carried manifold's deepest point stays near the narrowphase's.
    for (std::size_t i = 0, j = 0; i < recycling.contacts().size(); ++i) {
      const BodyContact& c = recycling.contacts()[i];
      while (!samePieces(fresh.contacts()[j], c)) ++j;
      const BodyContact& f = fresh.contacts()[j];
      double dc = -1e9, df = -1e9;
      for (int k = 0; k < c.manifold.count; ++k) dc = std::max(dc, c.manifold.points[k].depth);
      for (int k = 0; k < f.manifold.count; ++k) df = std::max(df, f.manifold.points[k].depth);
      if (c.recycled) worst_depth_gap = std::max(worst_depth_gap, std::abs(dc - df));
    }
  }
  std::printf(
      "recycled %zu, computed %zu contacts; %zu pairs began and %zu ended touching; "
      "deepest points of carried manifolds within %.2f mm of the narrowphase's; %zu "
      "bodies asleep at the end\n",
      recycled, computed, begun, ended, 1e3 * worst_depth_gap, recycling.sleepingCount());
  // The pile comes to rest: awake, most contacts are carried; asleep, they are not looked for.
  EXPECT_GT(recycled, settings.sleep.enabled ? computed / 4 : computed);
  EXPECT_GT(begun, 100u);
  EXPECT_GT(ended, 20u);
  EXPECT_LT(worst_depth_gap, 2 * settings.contact_recycle_distance);
}

class RecyclingWorld : public testing::TestWithParam<SolverKind> {};

TEST_P(RecyclingWorld, FindsExactlyTheNarrowphasesPairsAndReportsEveryBeginAndEnd) {
  WorldSettings settings;
  settings.solver.kind = GetParam();
  expectExactPairs(settings);
}

TEST(ContactRecycling, ExactWithSleepingIslands) {
  WorldSettings settings;
  settings.sleep.enabled = true;
  expectExactPairs(settings);
}

/// Each contact of `contacts` with an origin names one of `origins`, and a contact computed by
/// the narrowphase (not carried) names the origin made from its own points.
void expectOwnOrigins(std::span<const BodyContact> contacts,
                      std::span<const ManifoldOrigin> origins, std::size_t& checked) {
  for (const BodyContact& c : contacts) {
    if (c.origin == kNoOrigin) continue;
    ASSERT_LT(c.origin, origins.size());
    if (c.recycled) continue;
    const ManifoldOrigin& o = origins[c.origin];
    for (int i = 0; i < c.manifold.count; ++i) {
      ASSERT_EQ(o.point[i], c.manifold.points[i].position);
      ASSERT_EQ(o.depth[i], c.manifold.points[i].depth);
    }
    ++checked;
  }
}

TEST(ContactRecycling, OriginsFollowTheirContactsAsleepAndHeld) {
  // The origins live beside the contacts: contacts set aside while their island sleeps, or
  // while the level of detail holds their bodies, must find theirs again when they come back.
  WorldSettings settings;
  settings.sleep.enabled = true;
  settings.contact_recycle_distance = 0.01;
  World world(settings);
  for (const BodyDesc& d : tumblingPile()) {
    const BodyIndex i = world.addBody(d);
    if (i % 2 == 1 && d.type != BodyType::Static) world.setStepPeriod(i, 3);
  }
  std::size_t checked = 0, recycled = 0, asleep = 0;
  WarmStarts warm;
  for (int step = 0; step < 600; ++step) {
    world.step(kDt);
    recycled += world.recycledContacts();
    asleep = std::max(asleep, world.sleepingCount());
    expectOwnOrigins(world.contacts(), world.contactOrigins(), checked);
    world.warmStarts(warm);
    expectOwnOrigins(warm.contacts, warm.origins, checked);
    if (HasFatalFailure()) return;
  }
  std::printf("%zu contacts checked, %zu recycled, at most %zu bodies asleep\n", checked, recycled,
              asleep);
  EXPECT_GT(checked, 0u);
  EXPECT_GT(recycled, 0u);
  EXPECT_GT(asleep, 0u);
}

INSTANTIATE_TEST_SUITE_P(Solvers, RecyclingWorld,
                         testing::Values(SolverKind::GaussSeidel, SolverKind::SoftStep,
                                         SolverKind::SoftStepWide),
                         [](const testing::TestParamInfo<SolverKind>& info) {
                           switch (info.param) {
                             case SolverKind::GaussSeidel:
                               return std::string("GaussSeidel");
                             case SolverKind::SoftStep:
                               return std::string("SoftStep");
                             default:
                               return std::string("SoftStepWide");
                           }
                         });

}  // namespace
}  // namespace zonesim::physics
