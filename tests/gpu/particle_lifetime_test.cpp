// Lifetimes: particles die on the step their life runs out, stay dead (frozen, not integrated)
// and their slots are recycled lowest first; both backends agree on every count.

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>
#include <vector>

#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

class Lifetime : public ::testing::TestWithParam<Backend> {};

const Vec3d kGravity{0, -9.81, 0};

EmitSpec sprayAt(double y, double lifetime) {
  return EmitSpec{{0, y, 0}, {0, 1, 0}, 0.6, 5.0, lifetime};
}

TEST_P(Lifetime, ParticlesDieWhenTheirLifeRunsOut) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam());
  Pcg32 rng(7, 3);
  ASSERT_EQ(system.emit(sprayAt(1, 0.5), 100, rng), 100u);
  EXPECT_EQ(system.aliveCount(), 100u);
  // dt = 0.1 s: after 4 steps 0.1 s of life is left; the 5th step uses it up.
  for (int n = 0; n < 4; ++n) system.step(0.1, kGravity, 0.0, 0.5);
  EXPECT_EQ(system.aliveCount(), 100u);
  std::vector<Vec3d> before, after;
  system.readPositions(before);
  system.step(0.1, kGravity, 0.0, 0.5);
  EXPECT_EQ(system.aliveCount(), 0u);
  for (std::size_t i = 0; i < system.slotCount(); ++i) EXPECT_FALSE(system.isAlive(i));
  // Dead particles stay dead: no later step moves them.
  for (int n = 0; n < 10; ++n) system.step(0.1, kGravity, 0.0, 0.5);
  system.readPositions(after);
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(after[i].x, before[i].x);
    EXPECT_EQ(after[i].y, before[i].y);
    EXPECT_EQ(after[i].z, before[i].z);
  }
}

TEST_P(Lifetime, EmitRecyclesDeadSlotsLowestFirst) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam());
  Pcg32 rng(11, 5);
  system.emit(sprayAt(1, 10.0), 10, rng);  // slots 0-9, long-lived
  system.emit(sprayAt(1, 0.25), 10, rng);  // slots 10-19, gone after 3 steps of 0.1 s
  system.emit(sprayAt(1, 10.0), 10, rng);  // slots 20-29
  for (int n = 0; n < 3; ++n) system.step(0.1, kGravity, 0.1, 0.5);
  EXPECT_EQ(system.aliveCount(), 20u);
  EXPECT_FALSE(system.isAlive(10));
  EXPECT_TRUE(system.isAlive(20));

  ASSERT_EQ(system.emit(sprayAt(3, 1.0), 4, rng), 4u);
  EXPECT_EQ(system.slotCount(), 30u) << "dead slots must be filled before new ones";
  for (std::size_t s = 10; s < 14; ++s) EXPECT_TRUE(system.isAlive(s)) << s;
  for (std::size_t s = 14; s < 20; ++s) EXPECT_FALSE(system.isAlive(s)) << s;
  std::vector<Vec3d> pos;
  system.readPositions(pos);
  for (std::size_t s = 10; s < 14; ++s) EXPECT_EQ(pos[s].y, 3.0) << "slot " << s;

  ASSERT_EQ(system.emit(sprayAt(1, 1.0), 8, rng), 8u);  // 6 recycled, then 2 new
  EXPECT_EQ(system.slotCount(), 32u);
  EXPECT_EQ(system.aliveCount(), 32u);
}

TEST_P(Lifetime, EmitStopsAtTheParticleBudget) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam(), 50);
  Pcg32 rng(1, 2);
  EXPECT_EQ(system.emit(sprayAt(0, 0.2), 40, rng), 40u);
  EXPECT_EQ(system.emit(sprayAt(0, 0.2), 40, rng), 10u);
  EXPECT_EQ(system.aliveCount(), 50u);
  system.step(0.25, kGravity, 0.0, 0.5);
  EXPECT_EQ(system.aliveCount(), 0u);
  EXPECT_EQ(system.emit(sprayAt(0, 0.2), 40, rng), 40u);
  EXPECT_EQ(system.slotCount(), 50u);
}

TEST_P(Lifetime, RejectsInvalidArguments) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam());
  Pcg32 rng(1, 2);
  EXPECT_THROW(system.emit(sprayAt(-0.1, 1.0), 1, rng), std::invalid_argument);
  EXPECT_THROW(system.emit(sprayAt(0, 0.0), 1, rng), std::invalid_argument);
  EmitSpec no_direction = sprayAt(0, 1.0);
  no_direction.direction = {0, 0, 0};
  EXPECT_THROW(system.emit(no_direction, 1, rng), std::invalid_argument);
  EXPECT_THROW(system.step(0.0, kGravity, 0.0, 0.5), std::invalid_argument);
  EXPECT_THROW(system.step(0.1, kGravity, 20.0, 0.5), std::invalid_argument);
  EXPECT_THROW(system.step(0.1, kGravity, 0.0, 1.5), std::invalid_argument);
  EXPECT_THROW(system.step(0.1, {0, std::numeric_limits<double>::quiet_NaN(), 0}, 0.0, 0.5),
               std::invalid_argument);
  EXPECT_EQ(system.aliveCount(), 0u);
  EXPECT_EQ(system.slotCount(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, Lifetime, ::testing::Values(Backend::Cpu, Backend::OpenCl),
                         [](const auto& info) { return std::string(backendName(info.param)); });

}  // namespace
}  // namespace zonesim::gpu
