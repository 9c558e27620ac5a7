// The OpenCL backend keeps state on the device: one write per emit batch, one launch per step,
// reads only when asked, buffers that grow only past their capacity and keep their contents.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

const Vec3d kGravity{0, -9.81, 0};
const EmitSpec kSpray{{0, 1, 0}, {0, 1, 0}, 0.8, 8.0, 30.0};

TEST(Transfers, StepsMoveNoDataAndEmitsWriteOnce) {
  ZS_REQUIRE_OPENCL();
  ParticleSystem system = test::makeSystem(Backend::OpenCl);
  system.reserve(10'000);
  const std::size_t capacity = system.capacity();
  EXPECT_GE(capacity, 10'000u);
  Pcg32 rng(3, 4);
  system.emit(kSpray, 5'000, rng);
  TransferStats after_emit = system.transfers();
  EXPECT_EQ(after_emit.writes, 1u);
  EXPECT_EQ(after_emit.bytes_written, 5'000u * 32u);
  EXPECT_EQ(after_emit.reads, 0u);

  for (int n = 0; n < 100; ++n) system.step(1.0 / 60.0, kGravity, 0.1, 0.6);
  TransferStats after_steps = system.transfers();
  EXPECT_EQ(after_steps.writes, 1u);
  EXPECT_EQ(after_steps.reads, 0u);
  EXPECT_EQ(after_steps.launches, after_emit.launches + 100);

  system.emit(kSpray, 5'000, rng);
  std::vector<Vec3d> pos;
  system.readPositions(pos);
  TransferStats end = system.transfers();
  EXPECT_EQ(end.writes, 2u);
  EXPECT_EQ(end.reads, 3u);  // x, y and z arrays
  EXPECT_EQ(end.bytes_read, 3u * 10'000u * 4u);
  EXPECT_EQ(system.capacity(), capacity) << "reserved buffers must not be reallocated";
}

TEST(Transfers, CpuBackendReportsNoTraffic) {
  ParticleSystem system = test::makeSystem(Backend::Cpu);
  Pcg32 rng(3, 4);
  system.emit(kSpray, 100, rng);
  system.step(0.01, kGravity, 0.0, 0.5);
  EXPECT_EQ(system.transfers().writes, 0u);
  EXPECT_EQ(system.transfers().launches, 0u);
}

TEST(Transfers, GrowingTheBuffersKeepsTheState) {
  ZS_REQUIRE_OPENCL();
  ParticleSystem gpu = test::makeSystem(Backend::OpenCl);
  ParticleSystem cpu = test::makeSystem(Backend::Cpu);
  // 1,000 fit the first allocation (1,024 slots); 20,000 more force two device-side copies.
  for (ParticleSystem* system : {&gpu, &cpu}) {
    Pcg32 rng(5, 6);
    system->emit(kSpray, 1'000, rng);
    for (int n = 0; n < 30; ++n) system->step(1.0 / 60.0, kGravity, 0.1, 0.6);
    system->emit(kSpray, 20'000, rng);
    for (int n = 0; n < 30; ++n) system->step(1.0 / 60.0, kGravity, 0.1, 0.6);
  }
  std::vector<Vec3d> gp, cp;
  gpu.readPositions(gp);
  cpu.readPositions(cp);
  ASSERT_EQ(gp.size(), 21'000u);
  EXPECT_GE(gpu.capacity(), 21'000u);
  double worst = 0;
  for (std::size_t i = 0; i < gp.size(); ++i) {
    worst = std::max({worst, std::abs(gp[i].x - cp[i].x), std::abs(gp[i].y - cp[i].y),
                      std::abs(gp[i].z - cp[i].z)});
  }
  // Float rounding over 60 steps (see particle_reference_test.cpp); lost data would be metres.
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
}  // namespace zonesim::gpu
