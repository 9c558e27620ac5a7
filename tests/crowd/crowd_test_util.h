#pragma once
// Shared helpers for the crowd tests: owned arrays of agents and simple measurements.

#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "common/rng.h"
#include "crowd/agents.h"

namespace zonesim::crowd::test {

/// Owned storage for a set of agents, with a span view for the steps.
struct AgentArrays {
  std::vector<std::uint64_t> ids;
  std::vector<Vec2> pos;
  std::vector<Vec2> vel;
  AgentSpan span() { return AgentSpan{ids, pos, vel}; }
  GhostSpan ghosts() const { return GhostSpan{ids, pos, vel}; }
  void add(std::uint64_t id, Vec2 p, Vec2 v) {
    ids.push_back(id);
    pos.push_back(p);
    vel.push_back(v);
  }
};

/// 48 x 48 cells with two long walls whose gaps lie at opposite ends (a zig-zag): the base of
/// the flow tests' maps.
inline ai::GridMap zigZagMap() {
  ai::GridMap map(48, 48);
  for (int x = 0; x < 40; ++x) map.setPassable(x, 16, false);
  for (int x = 8; x < 48; ++x) map.setPassable(x, 32, false);
  return map;
}

/// Smallest distance between two agents (brute force).
inline double minPairDistance(const std::vector<Vec2>& pos) {
  double best = 1e300;
  for (std::size_t i = 0; i < pos.size(); ++i)
    for (std::size_t j = i + 1; j < pos.size(); ++j) {
      double d = length(pos[i] - pos[j]);
      if (d < best) best = d;
    }
  return best;
}

/// Largest distance of an agent from the centroid.
inline double radiusAboutCentroid(const std::vector<Vec2>& pos) {
  Vec2 c;
  for (Vec2 p : pos) c += p;
  c = c * (1.0 / double(pos.size()));
  double r = 0;
  for (Vec2 p : pos) r = std::max(r, length(p - c));
  return r;
}

/// n agents on a square lattice of the given spacing, random velocities up to vmax.
inline AgentArrays lattice(int side, double spacing, double vmax, std::uint64_t seed) {
  AgentArrays a;
  Pcg32 rng(seed, 7);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      a.add(1000 + std::uint64_t(y * side + x), Vec2{x * spacing, y * spacing},
            Vec2{rng.uniform(-vmax, vmax), rng.uniform(-vmax, vmax)});
  return a;
}

}  // namespace zonesim::crowd::test
