#include "zone_node/crowd/flock.h"

#include <stdexcept>

namespace zonesim::crowd {

Vec2 Flock::steering(const GridEntry& self, Vec2 goal, bool hasGoal) const {
  const FlockSettings& s = settings_;
  const double nr2 = s.neighbourRadius * s.neighbourRadius;
  const double sr = s.separationRadius, sr2 = sr * sr;
  Vec2 sep, sumVel, sumRel;
  // The loop is written without data-dependent branches for the common case (about a third
  // of the candidates from the cells are out of range, unpredictably): in-range flags multiply
  // the sums. The agent itself is a candidate at distance zero; it is taken out afterwards.
  double cnt = 0;
  grid_.forEachNear(self.pos, s.neighbourRadius, [&](const GridEntry& o) {
    Vec2 rel = o.pos - self.pos;
    double d2 = lengthSq(rel);
    double in = static_cast<double>(d2 < nr2);
    cnt += in;
    sumVel += o.vel * in;
    sumRel += rel * in;
    if (d2 < sr2) {
      if (d2 > 1e-18) {
        double d = std::sqrt(d2);
        // Unit vector away from the other, scaled by (sr / d - 1): zero at the radius,
        // unbounded as the distance goes to zero.
        sep += rel * (-(sr / d - 1.0) / d);
      } else if (o.id != self.id) {
        // Coincident agents: split them along x by id so the push is deterministic.
        sep.x += self.id < o.id ? -1e3 : 1e3;
      }
    }
  });
  // Remove the agent itself (counted once, with its own velocity; its rel is zero).
  int count = int(cnt) - 1;
  sumVel = sumVel - self.vel;
  Vec2 acc = sep * s.separationWeight;
  if (count > 0) {
    double inv = 1.0 / count;
    acc += (sumVel * inv - self.vel) * s.alignmentWeight;
    acc += sumRel * (inv * s.cohesionWeight);
  }
  if (hasGoal) acc += (goal - self.vel) * s.goalWeight;
  return clampLength(acc, s.maxForce);
}

void Flock::step(const AgentSpan& agents, const GhostSpan& ghosts, double dt,
                 std::span<const Vec2> goalVel, const StepPlan& plan) {
  const std::size_t n = agents.size();
  if (agents.pos.size() != n || agents.vel.size() != n || ghosts.pos.size() != ghosts.size() ||
      ghosts.vel.size() != ghosts.size() || (!goalVel.empty() && goalVel.size() != n) ||
      (!plan.empty() && (plan.dt.size() != n || plan.steer.size() != n)))
    throw std::invalid_argument("Flock::step: array sizes differ");
  grid_.build(agents, ghosts, 0.5 * settings_.neighbourRadius);
  const bool hasGoal = !goalVel.empty();
  // Owned agents in cell order: consecutive agents share most of their neighbour cells.
  for (const GridEntry& e : grid_.entries()) {
    if (e.src < 0) continue;
    const double h = plan.empty() ? dt : plan.dt[e.src];
    if (h <= 0.0) continue;
    Vec2 goal = hasGoal ? goalVel[e.src] : Vec2{};
    Vec2 acc;
    if (plan.empty() || plan.steer[e.src]) {
      acc = steering(e, goal, hasGoal);
    } else if (hasGoal) {
      acc = clampLength((goal - e.vel) * settings_.goalWeight, settings_.maxForce);
    }
    Vec2 v = clampLength(e.vel + acc * h, settings_.maxSpeed);
    agents.vel[e.src] = v;
    agents.pos[e.src] = e.pos + v * h;
  }
}

}  // namespace zonesim::crowd
