#pragma once
// Flocking (Reynolds boids): separation, alignment and cohesion over the neighbours found by
// the uniform grid, plus an optional goal velocity per agent (a flow field or a path can steer
// the flock through it, as the seed suggests for alignment). All agents read the state at the
// start of the step and write the new one (a Jacobi update), and neighbour sums run in the
// grid's canonical order, so the result is independent of storage order and of ownership.
// With a body radius, agents are discs that never step into each other (keep_apart.h); the
// gaps are a scalar pass after the sums, so every lane width still moves them alike.

#include <cstdint>
#include <span>
#include <vector>

#include "crowd/agents.h"
#include "crowd/keep_apart.h"
#include "crowd/neighbour_grid.h"
#include "crowd/step_plan.h"

namespace zonesim::crowd {

/// Flocking parameters; lengths in metres, times in seconds.
struct FlockSettings {
  double neighbour_radius = 3.0;    ///< alignment and cohesion see agents this close
  double separation_radius = 1.0;   ///< separation pushes apart agents closer than this
  double separation_weight = 20.0;  ///< 1/s^2 per unit of (radius / distance - 1)
  double alignment_weight = 1.0;    ///< 1/s: rate at which velocity follows the neighbours'
  double cohesion_weight = 0.5;     ///< 1/s^2: pull toward the neighbours' centre
  double goal_weight = 1.0;         ///< 1/s: rate at which velocity follows the goal velocity
  double max_speed = 2.0;           ///< m/s
  double max_force = 8.0;           ///< m/s^2, bound on the steering acceleration
  /// Agents are discs of this radius that never step into each other (keep_apart.h); 0: they
  /// may overlap, kept apart by separation alone. Holds for agents at full steering detail.
  double body_radius = 0.0;
  /// How far the caller shows every agent its neighbours (the zone's halo width): an agent
  /// keeping its gaps moves at most (sight - 2 body_radius) / 2 a step. Must exceed
  /// 2 body_radius.
  double sight = 1e9;
};

/// Scratch of the lane-wide neighbour sums: the candidates closer than the separation radius
/// to some lane of a group, and their (candidate, lane) pairs.
struct NotedScratch {
  std::vector<std::int32_t> k;      ///< noted candidates (entry indices), canonical order
  std::vector<std::uint8_t> lanes;  ///< per noted candidate: bit l set when close to lane l
  std::vector<std::uint8_t> lane;   ///< per pair: its lane
  std::vector<double> dx, dy;       ///< per pair: offset, then separation term
  /// Room for a group of `candidates` over up to 8 lanes (pairs padded to whole vectors).
  void reserve(std::size_t candidates) {
    if (k.size() >= candidates) return;
    k.resize(candidates);
    lanes.resize(candidates);
    const std::size_t pairs = candidates * 8 + 4;
    lane.resize(pairs);
    dx.resize(pairs);
    dy.resize(pairs);
  }
};

/// Steps flocks; owns the neighbour grid so that a warm step allocates nothing.
class Flock {
 public:
  /// A flock stepper with the given settings.
  explicit Flock(const FlockSettings& settings);

  /// Agents whose neighbour sums run in one pass: 1, 2 (SSE2), 4 (AVX) or 8 (AVX-512; the
  /// default, narrower where the CPU lacks it). Every width gives bitwise the same step;
  /// returns the width in use.
  int useLanes(int lanes);
  /// Advances `agents` by `dt` (semi-implicit Euler). `ghosts` are seen, not moved.
  /// `goal_vel`: empty, or a desired velocity per agent. `plan`: per-agent dt/detail (lod.h).
  void step(const AgentSpan& agents, const GhostSpan& ghosts, double dt,
            std::span<const Vec2> goal_vel = {}, const StepPlan& plan = {});

  /// The settings in use.
  const FlockSettings& settings() const { return settings_; }
  /// The grid of the last step (for inspection and reuse).
  const NeighbourGrid& grid() const { return grid_; }

 private:
  Vec2 steering(const GridEntry& self, Vec2 goal, bool hasGoal) const;

  FlockSettings settings_;
  NeighbourGrid grid_;
  int lanes_ = 1;
  NotedScratch noted_;    // candidates close enough to separate, per group
  KeepApart keep_apart_;  // the gaps of the agent being moved
};

}  // namespace zonesim::crowd
