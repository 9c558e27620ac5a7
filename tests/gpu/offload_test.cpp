// The per-workload offload decision: the crossover from probe samples and the auto choice, on
// made-up samples (no timing is asserted), plus the probe's plumbing on the real device.

#include "gpu/offload.h"

#include <gtest/gtest.h>

#include <vector>

#include "gpu/offload_probe.h"
#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

TEST(Crossover, InterpolatesBetweenTheLastLossAndTheFirstWin) {
  // Device 2x slower at 1,000, 2x faster at 4,000: log ratios -ln2 and +ln2 cross half-way in
  // log n, at 2,000.
  std::vector<ProbeSample> s{{1'000, 1.0, 2.0}, {4'000, 2.0, 1.0}, {16'000, 8.0, 1.0}};
  EXPECT_EQ(crossover(s), 2'000u);
}

TEST(Crossover, OrderOfSamplesDoesNotMatter) {
  std::vector<ProbeSample> s{{16'000, 8.0, 1.0}, {1'000, 1.0, 2.0}, {4'000, 2.0, 1.0}};
  EXPECT_EQ(crossover(s), 2'000u);
}

TEST(Crossover, DeviceWinningEverywhereGivesTheSmallestSize) {
  std::vector<ProbeSample> s{{1'000, 3.0, 1.0}, {4'000, 9.0, 1.0}};
  EXPECT_EQ(crossover(s), 1'000u);
}

TEST(Crossover, DeviceLosingAtTheLargestSizeNeverOffloads) {
  std::vector<ProbeSample> s{{1'000, 1.0, 2.0}, {4'000, 2.0, 1.0}, {16'000, 1.0, 1.5}};
  EXPECT_EQ(crossover(s), kNeverOffload);
  EXPECT_EQ(crossover({}), kNeverOffload);
}

TEST(Crossover, OnlyTheLastWinningRunCounts) {
  // A win at 1,000 that is lost again at 4,000 (noise or a cache step) is ignored.
  std::vector<ProbeSample> s{{1'000, 2.0, 1.0}, {4'000, 1.0, 2.0}, {16'000, 4.0, 1.0}};
  std::size_t t = crossover(s);
  EXPECT_GT(t, 4'000u);
  EXPECT_LE(t, 16'000u);
}

TEST(ChooseBackendPerWorkload, EachWorkloadHasItsOwnThreshold) {
  OffloadThresholds t;
  t.particles = 8'000;
  t.flock = 50'000;
  EXPECT_EQ(chooseBackend(GpuMode::Auto, Workload::Particles, 10'000, true, t), Backend::OpenCl);
  EXPECT_EQ(chooseBackend(GpuMode::Auto, Workload::Flock, 10'000, true, t), Backend::Cpu);
  EXPECT_EQ(chooseBackend(GpuMode::Auto, Workload::Flock, 50'000, true, t), Backend::OpenCl);
  t.flock = kNeverOffload;
  EXPECT_EQ(chooseBackend(GpuMode::Auto, Workload::Flock, 100'000'000, true, t), Backend::Cpu);
  EXPECT_EQ(chooseBackend(GpuMode::Auto, Workload::Particles, 10'000, false, t), Backend::Cpu);
}

TEST(ChooseBackendPerWorkload, OnAndOffIgnoreThresholds) {
  OffloadThresholds t;
  EXPECT_EQ(chooseBackend(GpuMode::On, Workload::Flock, 1, false, t), Backend::OpenCl);
  EXPECT_EQ(chooseBackend(GpuMode::Off, Workload::Particles, 100'000'000, true, t), Backend::Cpu);
}

TEST(ChooseBackendPerWorkload, DefaultsNameEveryWorkload) {
  OffloadThresholds t = defaultThresholds();
  EXPECT_EQ(t.of(Workload::Particles), kAutoGpuThreshold);
  EXPECT_EQ(t.of(Workload::Flock), kNeverOffload);
  EXPECT_STREQ(workloadName(Workload::Flock), "flock");
}

// The probe's plumbing on the real device, at sizes small enough for the test budget: one
// sample per size with positive times; what the times are is not asserted.
TEST(OffloadProbe, SamplesEverySizeOnBothPaths) {
  ZS_REQUIRE_OPENCL();
  const std::size_t sizes[] = {200, 800};
  std::vector<ProbeSample> s = probeParticles(test::sharedRuntime(), sizes);
  ASSERT_EQ(s.size(), 2u);
  for (const ProbeSample& p : s) {
    EXPECT_GT(p.cpu_s, 0.0);
    EXPECT_GT(p.device_s, 0.0);
  }
}

}  // namespace
}  // namespace zonesim::gpu
