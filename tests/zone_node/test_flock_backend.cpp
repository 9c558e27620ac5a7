#include <gtest/gtest.h>

#include "gpu/backend.h"
#include "test_helpers.h"
#include "zone_node/systems/flock_backend.h"
#include "zone_node/systems/flock_movement.h"

namespace zonesim::zone {
namespace {

TEST(FlockBackend, ModeAndPopulationPickTheBackend) {
  gpu::OffloadThresholds t;
  t.boids = 10'000;
  EXPECT_EQ(flockBackendFor("off", 1'000'000, t), gpu::Backend::Cpu);
  EXPECT_EQ(flockBackendFor("auto", 9'999, t), gpu::Backend::Cpu);
  // auto offloads from the threshold only where there is a device; on always asks for one.
  EXPECT_EQ(flockBackendFor("auto", 10'000, t),
            gpu::openClAvailable() ? gpu::Backend::OpenCl : gpu::Backend::Cpu);
  EXPECT_EQ(flockBackendFor("on", 10, t), gpu::Backend::OpenCl);
  t.boids = gpu::kNeverOffload;
  EXPECT_EQ(flockBackendFor("auto", 1'000'000, t), gpu::Backend::Cpu);
}

TEST(FlockBackend, FlockMovementReportsItsBackend) {
  Scene s = testing::npcScene(50);
  EXPECT_EQ(FlockMovement(s, "on").backendName(), "none");  // no flocking population
  NpcPopulation f;
  f.count = 100;
  f.flock.enabled = true;
  s.npcs.push_back(f);
  EXPECT_EQ(FlockMovement(s, "off").backendName(), "cpu");
  EXPECT_EQ(FlockMovement(s).backendName(), "cpu");  // off unless asked
  if (!gpu::openClAvailable()) GTEST_SKIP() << "no OpenCL device";
  EXPECT_EQ(FlockMovement(s, "on").backendName(), "opencl");
}

}  // namespace
}  // namespace zonesim::zone
