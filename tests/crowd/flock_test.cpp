// Flocking: a flock started on a loose lattice with random velocities keeps every pair at
// least a fixed fraction of the separation radius apart and stays within a radius bound of
// its centroid, while it settles into a common heading. Without the separation term the same
// flock collapses below the bound (the measurement detects a violation). With bodies kept
// apart, no pair of the same flock ever comes closer than two body radii, even without
// separation.

#include "crowd/flock.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "crowd_test_util.h"

namespace zonesim::crowd {
namespace {

struct FlockRun {
  double minDistance = 1e300;   // over all steps after the first second
  double maxRadius = 0;         // over all steps
  double finalSpeedSpread = 0;  // max |v - mean v| at the end
  int components = 0;           // groups linked by neighbour-radius contacts at the end
};

// Connected groups of agents, two agents linked when closer than `r` (union-find).
int components(const std::vector<Vec2>& pos, double r) {
  std::vector<int> parent(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i) parent[i] = int(i);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  int groups = int(pos.size());
  for (std::size_t i = 0; i < pos.size(); ++i)
    for (std::size_t j = i + 1; j < pos.size(); ++j)
      if (length(pos[i] - pos[j]) < r) {
        int a = find(int(i)), b = find(int(j));
        if (a != b) {
          parent[a] = b;
          --groups;
        }
      }
  return groups;
}

FlockRun runFlock(const FlockSettings& s, int side, double seconds) {
  auto a = test::lattice(side, 1.2 * s.separation_radius, 1.0, 21);
  Flock flock(s);
  const double dt = 1.0 / 30;
  FlockRun out;
  int steps = int(seconds / dt);
  for (int k = 0; k < steps; ++k) {
    flock.step(a.span(), {}, dt);
    if (k * dt >= 1.0) out.minDistance = std::min(out.minDistance, test::minPairDistance(a.pos));
    out.maxRadius = std::max(out.maxRadius, test::radiusAboutCentroid(a.pos));
  }
  Vec2 mean;
  for (Vec2 v : a.vel) mean += v;
  mean = mean * (1.0 / double(a.vel.size()));
  for (Vec2 v : a.vel) out.finalSpeedSpread = std::max(out.finalSpeedSpread, length(v - mean));
  out.components = components(a.pos, s.neighbour_radius);
  return out;
}

TEST(Flock, KeepsSeparationAndCohesion) {
  FlockSettings s;
  FlockRun r = runFlock(s, 12, 30.0);  // 144 agents, 30 s
  std::printf("min distance %.3f, max radius %.3f, velocity spread %.4f, groups %d\n",
              r.minDistance, r.maxRadius, r.finalSpeedSpread, r.components);
  EXPECT_GE(r.minDistance, 0.5 * s.separation_radius);
  EXPECT_LE(r.maxRadius, 12.0);
  EXPECT_EQ(r.components, 1);
  // Alignment: the flock ends with one common velocity (started with random ones up to 1.4).
  EXPECT_LT(r.finalSpeedSpread, 0.2);
}

TEST(Flock, WithoutSeparationTheFlockCollapses) {
  FlockSettings s;
  s.separation_weight = 0;
  FlockRun r = runFlock(s, 12, 30.0);
  std::printf("no separation: min distance %.3f, max radius %.3f\n", r.minDistance, r.maxRadius);
  EXPECT_LT(r.minDistance, 0.5 * s.separation_radius);
}

TEST(Flock, BodiesKeptApartNeverComeCloserThanTwoRadii) {
  FlockSettings s;
  s.body_radius = 0.5;  // the lattice starts 1.2 m apart: no overlap at the start
  for (double weight : {20.0, 0.0}) {
    s.separation_weight = weight;  // without separation, cohesion presses the flock together
    auto a = test::lattice(12, 1.2, 1.0, 21);
    Flock flock(s);
    double closest = 1e300;
    for (int k = 0; k < 300; ++k) {
      flock.step(a.span(), {}, 1.0 / 30);
      closest = std::min(closest, test::minPairDistance(a.pos));
    }
    std::printf("separation weight %g: closest pair %.6f m over 10 s (bodies 2 x 0.5 m)\n", weight,
                closest);
    EXPECT_GE(closest, 2 * s.body_radius - 1e-9) << "weight " << weight;
  }
}

TEST(Flock, BodiesNeedASightWiderThanTwoRadii) {
  FlockSettings s;
  s.body_radius = 1.0;
  s.sight = 2.0;
  EXPECT_THROW(Flock{s}, std::invalid_argument);
  s.body_radius = -0.1;
  EXPECT_THROW(Flock{s}, std::invalid_argument);
}

}  // namespace
}  // namespace zonesim::crowd
