// Bounces off static spheres: an exact head-on case, no particle ever ending inside a sphere,
// and the OpenCL kernel (float) against the CPU reference (double) in a spray over spheres.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

class SphereBounce : public ::testing::TestWithParam<Backend> {};

double distance(const Vec3d& a, const Vec3d& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

// Straight down onto the top of a sphere with no gravity and restitution 1: the particle comes
// back up at the same speed and, by the time of impact inside the step, to the mirrored height.
TEST_P(SphereBounce, HeadOnIsAMirror) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam());
  Pcg32 rng(1, 1);
  ASSERT_EQ(system.emit(EmitSpec{{0, 5.05, 0}, {0, -1, 0}, 0.0, 10.0, 10.0}, 1, rng), 1u);
  const Sphere rock{{0, 1, 0}, 2.0};  // top at y = 3
  // 0.1 s steps: 5.05 -> 4.05 -> 3.05 -> hits 3 at t = 0.05 of the third step, back to 3.95.
  for (int n = 0; n < 3; ++n) system.step(0.1, {0, 0, 0}, 0.0, 1.0, {&rock, 1});
  std::vector<Vec3d> x, v;
  system.readPositions(x);
  system.readVelocities(v);
  EXPECT_NEAR(x[0].y, 3.95, 1e-5);
  EXPECT_NEAR(v[0].y, 10.0, 1e-5);
  EXPECT_NEAR(x[0].x, 0.0, 1e-6);
  EXPECT_NEAR(x[0].z, 0.0, 1e-6);
}

// A spray from above onto three spheres: after every step, every live particle is outside every
// sphere (within float rounding) and none is below the ground.
TEST_P(SphereBounce, NoParticleEndsInsideASphere) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam());
  const std::vector<Sphere> rocks{{{0, 1, 0}, 1.5}, {{2.5, 0.5, 0.5}, 1.0}, {{-2, 2, -1}, 0.8}};
  Pcg32 rng(7, 3);
  system.emit(EmitSpec{{0, 6, 0}, {0, -1, 0}, 0.8, 4.0, 5.0}, 2000, rng);
  std::vector<Vec3d> x;
  for (int n = 0; n < 120; ++n) {
    system.step(1.0 / 60.0, {0, -9.81, 0}, 0.05, 0.6, rocks);
    system.readPositions(x);
    for (std::size_t i = 0; i < x.size(); ++i) {
      ASSERT_GE(x[i].y, 0.0) << "slot " << i << " step " << n;
      for (const Sphere& s : rocks) {
        ASSERT_GE(distance(x[i], s.center), s.radius - 1e-4) << "slot " << i << " step " << n;
      }
    }
  }
}

// A particle emitted inside a sphere is pushed out along the radius to the surface, and its
// inward velocity is reflected, within one step.
TEST_P(SphereBounce, ParticleStartingInsideIsPushedOut) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam());
  Pcg32 rng(2, 2);
  // 0.5 m right of the centre, moving inward (-x) at 1 m/s.
  ASSERT_EQ(system.emit(EmitSpec{{0.5, 2, 0}, {-1, 0, 0}, 0.0, 1.0, 10.0}, 1, rng), 1u);
  const Sphere rock{{0, 2, 0}, 1.0};
  system.step(0.01, {0, 0, 0}, 0.0, 1.0, {&rock, 1});
  std::vector<Vec3d> x, v;
  system.readPositions(x);
  system.readVelocities(v);
  EXPECT_NEAR(x[0].x, 1.0, 1e-6);
  EXPECT_NEAR(x[0].y, 2.0, 1e-6);
  EXPECT_NEAR(v[0].x, 1.0, 1e-6);
}

TEST_P(SphereBounce, RejectsANonPositiveRadius) {
  ZS_REQUIRE_BACKEND(GetParam());
  ParticleSystem system = test::makeSystem(GetParam());
  const Sphere bad{{0, 0, 0}, 0.0};
  EXPECT_THROW(system.step(0.01, {0, -9.81, 0}, 0.0, 0.5, {&bad, 1}), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Backends, SphereBounce, ::testing::Values(Backend::Cpu, Backend::OpenCl));

// Float tolerance for a spray over spheres, 240 steps of 1/60 s. Away from a contact decision
// the errors are those of the ground-only run (particle_reference_test.cpp: ~5e-5 m). A sphere
// contact, unlike the ground's, is a yes/no decision on the swept segment, and a grazing hit
// near a sphere's silhouette or a particle balanced on its top sends float and double to
// different sides: such a particle parts for good (metres). That is chaos, not a bug, so the
// bound is on the distribution: 99% of particles within 1e-3 m and the median within 1e-4 m;
// at most 1% parted. Measured on PoCL 3.1: median 5.1e-6 m, p99 4.0e-4 m, 51 of 10,000 parted
// beyond 1e-3 m. A wrong normal, a missed sphere or a different response parts thousands.
constexpr double kMedianTolerance = 1e-4;         // metres
constexpr double kP99Tolerance = 1e-3;            // metres
constexpr std::size_t kMaxPartedParticles = 100;  // of 10,000, beyond kP99Tolerance

TEST(SphereKernelVersusReference, SprayOverSpheres) {
  ZS_REQUIRE_OPENCL();
  ParticleSystem gpu = test::makeSystem(Backend::OpenCl);
  ParticleSystem cpu = test::makeSystem(Backend::Cpu);
  const std::vector<Sphere> rocks{
      {{0, 1, 0}, 1.5}, {{3, 0.5, 1}, 1.2}, {{-3, 2, -1}, 1.0}, {{1, 0, -3}, 2.0}};
  for (ParticleSystem* system : {&gpu, &cpu}) {
    Pcg32 rng(11, 5);
    for (int e = 0; e < 5; ++e) {
      EmitSpec spec{{-2.0 + e, 7.0, -1.0 + 0.5 * e}, {0, -1, 0}, 0.9, 3.0 + e, 60.0};
      ASSERT_EQ(system->emit(spec, 2000, rng), 2000u);
    }
  }
  std::vector<Vec3d> gp, cp, before, after;
  std::size_t contacts = 0;
  for (int n = 0; n < 240; ++n) {
    cpu.readVelocities(before);
    gpu.step(1.0 / 60.0, {0, -9.81, 0}, 0.1, 0.7, rocks);
    cpu.step(1.0 / 60.0, {0, -9.81, 0}, 0.1, 0.7, rocks);
    cpu.readVelocities(after);
    for (std::size_t i = 0; i < after.size(); ++i) {
      // Drag alone scales vx and vz by (1 - drag dt) and the ground touches only vy, so any
      // other change of the horizontal velocity is a sphere contact.
      double damp = 1.0 - 0.1 / 60.0;
      if (std::abs(after[i].x - before[i].x * damp) + std::abs(after[i].z - before[i].z * damp) >
          1e-9) {
        ++contacts;
      }
    }
  }
  gpu.readPositions(gp);
  cpu.readPositions(cp);
  std::vector<double> errors;
  for (std::size_t i = 0; i < cp.size(); ++i) {
    errors.push_back(std::max(
        {std::abs(gp[i].x - cp[i].x), std::abs(gp[i].y - cp[i].y), std::abs(gp[i].z - cp[i].z)}));
  }
  std::sort(errors.begin(), errors.end());
  double median = errors[errors.size() / 2];
  double p99 = errors[errors.size() * 99 / 100];
  std::size_t parted =
      std::count_if(errors.begin(), errors.end(), [](double e) { return e > kP99Tolerance; });
  std::cout << "spheres: |x_gpu - x_cpu| median " << median << " m, p99 " << p99 << " m over "
            << contacts << " sphere contacts; " << parted << " particles parted\n";
  RecordProperty("median_position_error_m", std::to_string(median));
  RecordProperty("p99_position_error_m", std::to_string(p99));
  EXPECT_GT(contacts, 2000u) << "the spray must really hit the spheres";
  EXPECT_LT(median, kMedianTolerance);
  EXPECT_LT(p99, kP99Tolerance);
  EXPECT_LE(parted, kMaxPartedParticles);
}

}  // namespace
}  // namespace zonesim::gpu
