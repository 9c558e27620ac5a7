// The OpenCL ground-plane flock's ghosts and argument checks; its accuracy against the crowd
// library's flock, the reference, is tested through zone_node's FlockBackend
// (tests/zone_node/test_flock_backend.cpp).

#include "gpu/planar_flock.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

constexpr double kDt = 0.05;

TEST(PlanarFlock, GhostsAreSeen) {
  ZS_REQUIRE_OPENCL();
  // An agent with a ghost 0.5 m to its east is pushed west; without the ghost it is not.
  PlanarFlock flock(PlanarFlockParams{}, test::sharedRuntime());
  std::vector<std::uint64_t> ids{1};
  std::vector<Vec2d> pos{{10, 10}}, vel{{0, 0}};
  std::vector<std::uint64_t> gid{2};
  std::vector<Vec2d> gpos{{10.5, 10}}, gvel{{0, 0}};
  flock.step(ids, pos, vel, PlanarAgents{gid, gpos, gvel}, kDt);
  EXPECT_LT(vel[0].x, -0.1);
  EXPECT_EQ(gpos[0].x, 10.5);  // ghosts are read only
  std::vector<Vec2d> alone{{10, 10}}, still{{0, 0}};
  flock.step(ids, alone, still, PlanarAgents{}, kDt);
  EXPECT_EQ(still[0].x, 0.0);
}

TEST(PlanarFlock, MismatchedLengthsThrow) {
  ZS_REQUIRE_OPENCL();
  PlanarFlock flock(PlanarFlockParams{}, test::sharedRuntime());
  std::vector<std::uint64_t> ids{1, 2};
  std::vector<Vec2d> pos{{0, 0}}, vel{{0, 0}, {0, 0}};
  EXPECT_THROW(flock.step(ids, pos, vel, PlanarAgents{}, kDt), std::invalid_argument);
}

}  // namespace
}  // namespace zonesim::gpu
