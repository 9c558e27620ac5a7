// FlockBackend: which backend a population gets, and the OpenCL flock (gpu/planar_flock.h,
// float) against the crowd library's flock (double), its reference: one step from the same
// agents and ghosts, per-agent velocity error.

#include "zone_node/systems/flock_backend.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

#include "common/rng.h"
#include "gpu/backend.h"
#include "zone_node/zone_fixture.h"
#include "zone_node/systems/flock_movement.h"

namespace zonesim::zone {
namespace {

constexpr double kDt = 0.05;  // the zone scenes' tick

crowd::FlockSettings settings() {
  crowd::FlockSettings s;  // the scene defaults: radius 3, separation 1 m at weight 20, ...
  s.goal_weight = 0.8;
  return s;
}

/// A zone's flockers and the ghosts in its halo: owned agents in a 60 m square far from the
/// origin (x near 5,000 m: float positions there are only good to 5e-4 m, so the device must
/// work with offsets), about 12 neighbours each, ghosts in a 3 m strip past its east edge
/// (the halo), a few exact overlaps among the owned agents and with ghosts.
struct FlockCase {
  std::vector<std::uint64_t> ids, ghost_ids;
  std::vector<crowd::Vec2> pos, vel, ghost_pos, ghost_vel;
};

FlockCase makeCase() {
  FlockCase s;
  Pcg32 rng(11, 3);
  const double x0 = 5000, y0 = -3000;
  for (std::uint64_t i = 0; i < 4800; ++i) {
    s.ids.push_back(1000 + 7 * i);
    s.pos.push_back({x0 + rng.uniform(0, 60), y0 + rng.uniform(0, 60)});
    s.vel.push_back({rng.uniform(-2, 2), rng.uniform(-2, 2)});
  }
  for (std::uint64_t i = 0; i < 240; ++i) {
    s.ghost_ids.push_back(3 + 7 * i);  // disjoint from the owned ids
    s.ghost_pos.push_back({x0 + 60 + rng.uniform(0, 3), y0 + rng.uniform(0, 60)});
    s.ghost_vel.push_back({rng.uniform(-2, 2), rng.uniform(-2, 2)});
  }
  // Exact overlaps: owned on owned, owned on a ghost.
  for (std::size_t i = 0; i < 10; ++i) s.pos[100 + i] = s.pos[200 + i];
  s.ghost_pos[5] = s.pos[300] = {x0 + 60.5, y0 + 30};
  return s;
}

/// Per-agent velocity error of one step, device against the double reference.
struct Errors {
  std::vector<double> velocity;  ///< |v_device - v_reference|, m/s, per owned agent
  double max_position = 0;       ///< m
  double median() const { return at(0.5); }
  double at(double q) const {
    std::vector<double> e = velocity;
    std::sort(e.begin(), e.end());
    return e[std::size_t(q * double(e.size() - 1))];
  }
  double max() const { return *std::max_element(velocity.begin(), velocity.end()); }
};

Errors compareOneStep(const FlockCase& s, const std::vector<crowd::Vec2>& goal,
                      const std::vector<double>& agent_dt, const std::vector<std::uint8_t>& steer) {
  crowd::Flock reference(settings());
  std::vector<crowd::Vec2> pos = s.pos, vel = s.vel;
  reference.step(crowd::AgentSpan{s.ids, pos, vel},
                 crowd::GhostSpan{s.ghost_ids, s.ghost_pos, s.ghost_vel}, kDt, goal,
                 crowd::StepPlan{agent_dt, steer});

  FlockBackend device(settings(), gpu::Backend::OpenCl);
  std::vector<crowd::Vec2> dpos = s.pos, dvel = s.vel;
  device.step(crowd::AgentSpan{s.ids, dpos, dvel},
              crowd::GhostSpan{s.ghost_ids, s.ghost_pos, s.ghost_vel}, kDt, goal,
              crowd::StepPlan{agent_dt, steer});

  Errors e;
  for (std::size_t i = 0; i < pos.size(); ++i) {
    e.velocity.push_back(std::hypot(dvel[i].x - vel[i].x, dvel[i].y - vel[i].y));
    e.max_position =
        std::max(e.max_position, std::hypot(dpos[i].x - pos[i].x, dpos[i].y - pos[i].y));
  }
  return e;
}

// Float sums of ~12 neighbours, offsets good to a float ulp of the 3 m cell (2.4e-7 m), give
// velocity errors ~1e-6 m/s. Larger ones come from a neighbour whose distance rounds across
// the 3 m radius: it joins one path's alignment and cohesion and not the other's, a jump of
// up to dt (alignment * 2 max speed + cohesion * radius) / count = 0.05 * 5.5 / 12 = 2e-2
// m/s, and from separation near an overlap (1/d). The bounds: median 1e-6 m/s, p99 1e-5 m/s,
// max 3e-2 m/s; positions move by v dt, so 1.5e-3 m at most.
constexpr double kMedianVelocity = 1e-6;
constexpr double kP99Velocity = 1e-5;
constexpr double kMaxVelocity = 3e-2;
constexpr double kMaxPosition = kMaxVelocity * kDt;

void expectWithinBounds(const Errors& e, const char* what) {
  std::cout << what << ": velocity error median " << e.median() << " m/s, p99 " << e.at(0.99)
            << ", max " << e.max() << "; position max " << e.max_position << " m\n";
  EXPECT_LT(e.median(), kMedianVelocity);
  EXPECT_LT(e.at(0.99), kP99Velocity);
  EXPECT_LT(e.max(), kMaxVelocity);
  EXPECT_LT(e.max_position, kMaxPosition);
}

TEST(FlockBackend, OpenClStepWithGhostsMatchesTheCrowdFlock) {
  if (!gpu::openClAvailable()) GTEST_SKIP() << "no OpenCL device";
  expectWithinBounds(compareOneStep(makeCase(), {}, {}, {}), "flock + ghosts");
}

TEST(FlockBackend, OpenClGoalsAndPerAgentStepsMatchTheCrowdFlock) {
  if (!gpu::openClAvailable()) GTEST_SKIP() << "no OpenCL device";
  FlockCase s = makeCase();
  std::vector<crowd::Vec2> goal;
  std::vector<double> dt;
  std::vector<std::uint8_t> steer;
  Pcg32 rng(4, 9);
  for (std::size_t i = 0; i < s.ids.size(); ++i) {
    goal.push_back({rng.uniform(-2, 2), rng.uniform(-2, 2)});
    dt.push_back(i % 5 == 0 ? 0.0 : (i % 5 == 1 ? 2 * kDt : kDt));  // skipped, catching up
    steer.push_back(i % 3 != 0);                                    // cheap update: goal only
  }
  Errors e = compareOneStep(s, goal, dt, steer);
  expectWithinBounds(e, "goals + per-agent dt");
}

TEST(FlockBackend, ModeAndPopulationPickTheBackend) {
  gpu::OffloadThresholds t;
  t.flock = 10'000;
  EXPECT_EQ(flockBackendFor("off", 1'000'000, t), gpu::Backend::Cpu);
  EXPECT_EQ(flockBackendFor("auto", 9'999, t), gpu::Backend::Cpu);
  // auto offloads from the threshold only where there is a device; on always asks for one.
  EXPECT_EQ(flockBackendFor("auto", 10'000, t),
            gpu::openClAvailable() ? gpu::Backend::OpenCl : gpu::Backend::Cpu);
  EXPECT_EQ(flockBackendFor("on", 10, t), gpu::Backend::OpenCl);
  t.flock = gpu::kNeverOffload;
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
  // auto weighs a zone's share: 100 flockers on 2 ranks are 50 per zone, below 60.
  gpu::OffloadThresholds t;
  t.flock = 60;
  EXPECT_EQ(FlockMovement(s, "auto", t, 2).backendName(), "cpu");
  if (!gpu::openClAvailable()) GTEST_SKIP() << "no OpenCL device";
  EXPECT_EQ(FlockMovement(s, "auto", t, 1).backendName(), "opencl");
  EXPECT_EQ(FlockMovement(s, "on").backendName(), "opencl");
}

}  // namespace
}  // namespace zonesim::zone
