#include "zone_node/crowd/flock.h"

#include <stdexcept>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace zonesim::crowd {

namespace {

// Neighbour sums of one agent: the count and velocity sum of agents within the neighbour
// radius, the sum of their offsets, and the separation push. Includes the agent itself (at
// offset zero), which the caller takes out.
struct NeighbourSums {
  double count = 0;
  Vec2 vel, rel, sep;
  int coincident = 0;  // entries at distance zero (the agent itself and exact overlaps)
};

#if !defined(__SSE2__)
// One candidate at a time (targets without SSE2).
void accumulateScalar(const NeighbourGrid& g, std::int32_t begin, std::int32_t end, Vec2 p,
                      double nr2, double sr, NeighbourSums& s) {
  const double sr2 = sr * sr;
  for (std::int32_t k = begin; k < end; ++k) {
    Vec2 rel{g.xs()[k] - p.x, g.ys()[k] - p.y};
    double d2 = lengthSq(rel);
    double in = static_cast<double>(d2 < nr2);
    s.count += in;
    s.vel += Vec2{g.vxs()[k], g.vys()[k]} * in;
    s.rel += rel * in;
    if (d2 < sr2) {
      if (d2 > 1e-18) {
        double d = std::sqrt(d2);
        // Unit vector away from the other, scaled by (sr / d - 1): zero at the radius,
        // unbounded as the distance goes to zero.
        s.sep += rel * (-(sr / d - 1.0) / d);
      } else {
        ++s.coincident;
      }
    }
  }
}

#else
// Two candidates per instruction (SSE2 is part of x86-64) for the distances and terms; the
// terms are then added one lane after the other into scalar sums (the low lanes), so a sum is
// the sequential sum over the in-range neighbours in canonical order. Out-of-range candidates
// add exact zeros. Summing per lane instead would pair candidates by their position in the
// row, which shifts when a cell holds agents out of range that another rank's halo leaves out
// (a zone run then differs from a single rank in the last bit). In-range masks replace
// branches: about a third of the candidates from the cells fall outside the radius.
struct Lanes {
  __m128d count = _mm_setzero_pd(), vx = _mm_setzero_pd(), vy = _mm_setzero_pd();
  __m128d rx = _mm_setzero_pd(), ry = _mm_setzero_pd(), sx = _mm_setzero_pd();
  __m128d sy = _mm_setzero_pd();
  int coincident = 0;
};

// acc + c[0] + c[1], in that order, in the low lane.
inline __m128d addInOrder(__m128d acc, __m128d c) {
  return _mm_add_sd(_mm_add_sd(acc, c), _mm_unpackhi_pd(c, c));
}

inline void accumulatePair(__m128d x, __m128d y, __m128d vx, __m128d vy, __m128d lanes, __m128d px,
                           __m128d py, __m128d nr2, __m128d sr, Lanes& a) {
  const __m128d one = _mm_set1_pd(1.0);
  __m128d dx = _mm_sub_pd(x, px), dy = _mm_sub_pd(y, py);
  __m128d d2 = _mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy));
  __m128d in = _mm_and_pd(_mm_cmplt_pd(d2, nr2), lanes);
  a.count = addInOrder(a.count, _mm_and_pd(in, one));
  a.vx = addInOrder(a.vx, _mm_and_pd(in, vx));
  a.vy = addInOrder(a.vy, _mm_and_pd(in, vy));
  a.rx = addInOrder(a.rx, _mm_and_pd(in, dx));
  a.ry = addInOrder(a.ry, _mm_and_pd(in, dy));
  __m128d close = _mm_and_pd(_mm_cmplt_pd(d2, _mm_mul_pd(sr, sr)), lanes);
  if (_mm_movemask_pd(close)) {
    __m128d zero = _mm_cmple_pd(d2, _mm_set1_pd(1e-18));
    a.coincident += __builtin_popcount(unsigned(_mm_movemask_pd(_mm_and_pd(close, zero))));
    __m128d push = _mm_andnot_pd(zero, close);
    __m128d d = _mm_sqrt_pd(_mm_or_pd(d2, _mm_and_pd(zero, one)));  // no sqrt(0) / 0
    __m128d w = _mm_div_pd(_mm_sub_pd(_mm_div_pd(sr, d), one), d);
    w = _mm_and_pd(push, w);
    // Subtracting dx * w: adding its negation (exact) in lane order.
    const __m128d sign = _mm_set1_pd(-0.0);
    a.sx = addInOrder(a.sx, _mm_xor_pd(_mm_mul_pd(dx, w), sign));
    a.sy = addInOrder(a.sy, _mm_xor_pd(_mm_mul_pd(dy, w), sign));
  }
}

double lowLane(__m128d v) {
  return _mm_cvtsd_f64(v);  // the sums run in the low lane; the high one is unused
}
#endif

NeighbourSums neighbourSums(const NeighbourGrid& g, Vec2 p, double nr, double sr) {
  NeighbourSums s;
  const double nr2 = nr * nr;
#if defined(__SSE2__)
  Lanes a;
  const __m128d px = _mm_set1_pd(p.x), py = _mm_set1_pd(p.y), nr2v = _mm_set1_pd(nr2);
  const __m128d srv = _mm_set1_pd(sr);
  const __m128d both = _mm_castsi128_pd(_mm_set1_epi64x(-1));
  const __m128d low = _mm_castsi128_pd(_mm_set_epi64x(0, -1));
  g.forEachRowNear(p, nr, [&](std::int32_t begin, std::int32_t end) {
    std::int32_t k = begin;
    for (; k + 2 <= end; k += 2)
      accumulatePair(_mm_loadu_pd(g.xs() + k), _mm_loadu_pd(g.ys() + k), _mm_loadu_pd(g.vxs() + k),
                     _mm_loadu_pd(g.vys() + k), both, px, py, nr2v, srv, a);
    if (k < end)
      accumulatePair(_mm_load_sd(g.xs() + k), _mm_load_sd(g.ys() + k), _mm_load_sd(g.vxs() + k),
                     _mm_load_sd(g.vys() + k), low, px, py, nr2v, srv, a);
  });
  s.count = lowLane(a.count);
  s.vel = Vec2{lowLane(a.vx), lowLane(a.vy)};
  s.rel = Vec2{lowLane(a.rx), lowLane(a.ry)};
  s.sep = Vec2{lowLane(a.sx), lowLane(a.sy)};
  s.coincident = a.coincident;
#else
  g.forEachRowNear(p, nr, [&](std::int32_t begin, std::int32_t end) {
    accumulateScalar(g, begin, end, p, nr2, sr, s);
  });
#endif
  return s;
}

}  // namespace

Vec2 Flock::steering(const GridEntry& self, Vec2 goal, bool hasGoal) const {
  const FlockSettings& s = settings_;
  NeighbourSums n = neighbourSums(grid_, self.pos, s.neighbourRadius, s.separationRadius);
  if (n.coincident > 1) {
    // Exact overlaps besides the agent itself (rare): split them along x by id so that the
    // push is deterministic.
    grid_.forEachNear(self.pos, s.neighbourRadius, [&](const GridEntry& o) {
      if (o.id != self.id && lengthSq(o.pos - self.pos) <= 1e-18)
        n.sep.x += self.id < o.id ? -1e3 : 1e3;
    });
  }
  // Take out the agent itself: counted once, with its own velocity; its offset is zero.
  int count = int(n.count) - 1;
  Vec2 acc = n.sep * s.separationWeight;
  if (count > 0) {
    double inv = 1.0 / count;
    acc += ((n.vel - self.vel) * inv - self.vel) * s.alignmentWeight;
    acc += n.rel * (inv * s.cohesionWeight);
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
  grid_.build(agents, ghosts, settings_.neighbourRadius);
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
