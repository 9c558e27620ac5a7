// Crowd batch integration: the bounded-acceleration approach to a desired velocity in closed
// form on both backends, and the OpenCL kernel (float) against the CPU reference (double).

#include "gpu/crowd_batch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

class Crowd : public ::testing::TestWithParam<Backend> {};

CrowdBatch makeBatch(Backend backend) {
  return CrowdBatch(backend, backend == Backend::OpenCl ? test::sharedRuntime() : nullptr);
}

// From rest toward 3 m/s along x with a_max = 2 m/s^2 and dt = 0.1 s: v = 0.2 n until it reaches
// 3 m/s at step 15, then stays; x is the sum of the velocities times dt.
TEST_P(Crowd, ReachesTheDesiredVelocityAtTheBoundedRate) {
  ZS_REQUIRE_BACKEND(GetParam());
  CrowdBatch batch = makeBatch(GetParam());
  const std::vector<Vec3d> start{{0, 0, 0}};
  batch.setAgents(start, start);
  const std::vector<Vec3d> desired{{3, 0, 0}};
  double expected_x = 0;
  std::vector<Vec3d> x, v;
  for (int n = 1; n <= 20; ++n) {
    batch.step(desired, 0.1, 2.0);
    double expected_v = std::min(0.2 * n, 3.0);
    expected_x += expected_v * 0.1;
    batch.readVelocities(v);
    batch.readPositions(x);
    ASSERT_NEAR(v[0].x, expected_v, 1e-5) << "step " << n;
    ASSERT_NEAR(x[0].x, expected_x, 1e-5) << "step " << n;
    ASSERT_EQ(v[0].y, 0.0);
  }
}

TEST_P(Crowd, RejectsMismatchedOrInvalidInput) {
  ZS_REQUIRE_BACKEND(GetParam());
  CrowdBatch batch = makeBatch(GetParam());
  const std::vector<Vec3d> two(2), one(1);
  EXPECT_THROW(batch.setAgents(two, one), std::invalid_argument);
  batch.setAgents(two, two);
  EXPECT_THROW(batch.step(one, 0.1, 1.0), std::invalid_argument);
  EXPECT_THROW(batch.step(two, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(batch.step(two, 0.1, -1.0), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Backends, Crowd, ::testing::Values(Backend::Cpu, Backend::OpenCl));

// Float tolerance, 300 steps of 1/20 s with desired velocities redrawn every 20 steps. Agents are
// independent and the step is a contraction toward the desired velocity, so errors do not grow
// exponentially: each step adds a few roundings (~2e-7 relative) of velocities up to 5 m/s and
// positions up to ~100 m (~1e-5 m apart per rounding), and the velocity error is pulled back to
// the float rounding of desired. Measured on PoCL 3.1: 1.5e-4 m and 1.4e-6 m/s (7x headroom).
constexpr double kPositionTolerance = 1e-3;  // metres
constexpr double kVelocityTolerance = 1e-5;  // metres per second

TEST(CrowdKernelVersusReference, ThreeHundredStepsOfChangingGoals) {
  ZS_REQUIRE_OPENCL();
  const std::size_t n = 20'000;
  Pcg32 rng(8, 8);
  std::vector<Vec3d> x(n), v(n), desired(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = {rng.uniform(-50, 50), 0, rng.uniform(-50, 50)};
    v[i] = {rng.uniform(-1, 1), 0, rng.uniform(-1, 1)};
  }
  CrowdBatch gpu = makeBatch(Backend::OpenCl);
  CrowdBatch cpu = makeBatch(Backend::Cpu);
  gpu.setAgents(x, v);
  cpu.setAgents(x, v);
  for (int s = 0; s < 300; ++s) {
    if (s % 20 == 0) {
      for (Vec3d& d : desired) d = {rng.uniform(-3.5, 3.5), 0, rng.uniform(-3.5, 3.5)};
    }
    gpu.step(desired, 0.05, 4.0);
    cpu.step(desired, 0.05, 4.0);
  }
  std::vector<Vec3d> gx, gv, cx, cv;
  gpu.readPositions(gx);
  gpu.readVelocities(gv);
  cpu.readPositions(cx);
  cpu.readVelocities(cv);
  double ex = 0, ev = 0;
  for (std::size_t i = 0; i < n; ++i) {
    ex = std::max({ex, std::abs(gx[i].x - cx[i].x), std::abs(gx[i].z - cx[i].z)});
    ev = std::max({ev, std::abs(gv[i].x - cv[i].x), std::abs(gv[i].z - cv[i].z)});
  }
  std::cout << "crowd: max |x_gpu - x_cpu| = " << ex << " m, max |v_gpu - v_cpu| = " << ev
            << " m/s after 300 steps\n";
  RecordProperty("max_position_error_m", std::to_string(ex));
  RecordProperty("max_velocity_error_mps", std::to_string(ev));
  EXPECT_LT(ex, kPositionTolerance);
  EXPECT_LT(ev, kVelocityTolerance);
}

}  // namespace
}  // namespace zonesim::gpu
