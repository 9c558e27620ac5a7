#include "zone_node/crowd/flock.h"

#include <stdexcept>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

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
    int m = _mm_movemask_pd(_mm_and_pd(close, zero));
    a.coincident += (m & 1) + (m >> 1);  // baseline x86-64 has no popcnt instruction
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

double highLane(__m128d v) {
  return _mm_cvtsd_f64(_mm_unpackhi_pd(v, v));
}

// Two agents at once, one per lane: each candidate is broadcast to both lanes and added to
// each lane's sums, so each lane is the sequential sum over its agent's in-range neighbours in
// canonical order (the candidates of the union of both agents' rows come in canonical order,
// and the ones out of an agent's reach add exact zeros to its sums, which are never -0). The
// lanes' sums are therefore bitwise those of the one-agent loop, at one add per term and
// candidate for two agents instead of two adds per term and candidate pair for one.
struct PairLanes {
  __m128d count = _mm_setzero_pd(), vx = _mm_setzero_pd(), vy = _mm_setzero_pd();
  __m128d rx = _mm_setzero_pd(), ry = _mm_setzero_pd(), sx = _mm_setzero_pd();
  __m128d sy = _mm_setzero_pd();
  int coincident[2] = {0, 0};
};

inline void accumulateBroadcast(const NeighbourGrid& g, std::int32_t k, __m128d px, __m128d py,
                                __m128d nr2, __m128d sr, __m128d sr2, PairLanes& a) {
  const __m128d one = _mm_set1_pd(1.0);
  __m128d dx = _mm_sub_pd(_mm_load1_pd(g.xs() + k), px);
  __m128d dy = _mm_sub_pd(_mm_load1_pd(g.ys() + k), py);
  __m128d d2 = _mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy));
  __m128d in = _mm_cmplt_pd(d2, nr2);
  a.count = _mm_add_pd(a.count, _mm_and_pd(in, one));
  a.vx = _mm_add_pd(a.vx, _mm_and_pd(in, _mm_load1_pd(g.vxs() + k)));
  a.vy = _mm_add_pd(a.vy, _mm_and_pd(in, _mm_load1_pd(g.vys() + k)));
  a.rx = _mm_add_pd(a.rx, _mm_and_pd(in, dx));
  a.ry = _mm_add_pd(a.ry, _mm_and_pd(in, dy));
  __m128d close = _mm_cmplt_pd(d2, sr2);
  if (_mm_movemask_pd(close)) {
    __m128d zero = _mm_cmple_pd(d2, _mm_set1_pd(1e-18));
    int m = _mm_movemask_pd(_mm_and_pd(close, zero));
    a.coincident[0] += m & 1;
    a.coincident[1] += m >> 1;
    __m128d push = _mm_andnot_pd(zero, close);
    __m128d d = _mm_sqrt_pd(_mm_or_pd(d2, _mm_and_pd(zero, one)));  // no sqrt(0) / 0
    __m128d w = _mm_and_pd(push, _mm_div_pd(_mm_sub_pd(_mm_div_pd(sr, d), one), d));
    const __m128d sign = _mm_set1_pd(-0.0);
    a.sx = _mm_add_pd(a.sx, _mm_xor_pd(_mm_mul_pd(dx, w), sign));
    a.sy = _mm_add_pd(a.sy, _mm_xor_pd(_mm_mul_pd(dy, w), sign));
  }
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

#if defined(__x86_64__) && defined(__GNUC__)
#define ZONESIM_FLOCK_AVX 1

// Four agents at once, one per lane of an AVX register, on the same scheme as PairLanes
// (each lane is the sequential sum over its agent's in-range neighbours in canonical order).
// AVX without FMA: every product is rounded before it is added, exactly as in the SSE2 loops,
// so the lanes are bitwise the one-agent sums. Chosen at run time (CPUs without AVX take the
// SSE2 pairs); the target attribute keeps the rest of the library baseline x86-64.
struct QuadSums {
  double count[4], vx[4], vy[4], rx[4], ry[4], sx[4], sy[4];
  int coincident[4] = {0, 0, 0, 0};
};

// Rows of the union of the four discs, at most this many (else the caller takes two pairs).
constexpr int kQuadRows = 16;

__attribute__((target("avx"))) void neighbourSumsQuad(const NeighbourGrid& g, const Vec2* p,
                                                      const std::int32_t* ranges, int rows,
                                                      double nr, double sr, QuadSums& out) {
  const __m256d px = _mm256_set_pd(p[3].x, p[2].x, p[1].x, p[0].x);
  const __m256d py = _mm256_set_pd(p[3].y, p[2].y, p[1].y, p[0].y);
  const __m256d nr2 = _mm256_set1_pd(nr * nr), srv = _mm256_set1_pd(sr);
  const __m256d sr2 = _mm256_set1_pd(sr * sr), one = _mm256_set1_pd(1.0);
  const __m256d tiny = _mm256_set1_pd(1e-18), sign = _mm256_set1_pd(-0.0);
  __m256d count = _mm256_setzero_pd(), vx = _mm256_setzero_pd(), vy = _mm256_setzero_pd();
  __m256d rx = _mm256_setzero_pd(), ry = _mm256_setzero_pd(), sx = _mm256_setzero_pd();
  __m256d sy = _mm256_setzero_pd();
  int* coincident = out.coincident;
  for (int r = 0; r < rows; ++r) {
    for (std::int32_t k = ranges[2 * r]; k < ranges[2 * r + 1]; ++k) {
      __m256d dx = _mm256_sub_pd(_mm256_broadcast_sd(g.xs() + k), px);
      __m256d dy = _mm256_sub_pd(_mm256_broadcast_sd(g.ys() + k), py);
      __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
      __m256d in = _mm256_cmp_pd(d2, nr2, _CMP_LT_OQ);
      count = _mm256_add_pd(count, _mm256_and_pd(in, one));
      vx = _mm256_add_pd(vx, _mm256_and_pd(in, _mm256_broadcast_sd(g.vxs() + k)));
      vy = _mm256_add_pd(vy, _mm256_and_pd(in, _mm256_broadcast_sd(g.vys() + k)));
      rx = _mm256_add_pd(rx, _mm256_and_pd(in, dx));
      ry = _mm256_add_pd(ry, _mm256_and_pd(in, dy));
      __m256d close = _mm256_cmp_pd(d2, sr2, _CMP_LT_OQ);
      if (_mm256_movemask_pd(close)) {
        __m256d zero = _mm256_cmp_pd(d2, tiny, _CMP_LE_OQ);
        int m = _mm256_movemask_pd(_mm256_and_pd(close, zero));
        for (int l = 0; l < 4; ++l) coincident[l] += (m >> l) & 1;
        __m256d push = _mm256_andnot_pd(zero, close);
        __m256d d = _mm256_sqrt_pd(_mm256_or_pd(d2, _mm256_and_pd(zero, one)));
        __m256d w =
            _mm256_and_pd(push, _mm256_div_pd(_mm256_sub_pd(_mm256_div_pd(srv, d), one), d));
        sx = _mm256_add_pd(sx, _mm256_xor_pd(_mm256_mul_pd(dx, w), sign));
        sy = _mm256_add_pd(sy, _mm256_xor_pd(_mm256_mul_pd(dy, w), sign));
      }
    }
  }
  _mm256_storeu_pd(out.count, count);
  _mm256_storeu_pd(out.vx, vx);
  _mm256_storeu_pd(out.vy, vy);
  _mm256_storeu_pd(out.rx, rx);
  _mm256_storeu_pd(out.ry, ry);
  _mm256_storeu_pd(out.sx, sx);
  _mm256_storeu_pd(out.sy, sy);
}
#endif

// The sums of two agents in one pass over the union of their rows (see PairLanes).
void neighbourSumsPair(const NeighbourGrid& g, Vec2 p, Vec2 q, double nr, double sr,
                       NeighbourSums& sp, NeighbourSums& sq) {
#if defined(__SSE2__)
  PairLanes a;
  const __m128d px = _mm_set_pd(q.x, p.x), py = _mm_set_pd(q.y, p.y);
  const __m128d nr2 = _mm_set1_pd(nr * nr), srv = _mm_set1_pd(sr), sr2 = _mm_set1_pd(sr * sr);
  g.forEachRowNearEither(p, q, nr, [&](std::int32_t begin, std::int32_t end) {
    for (std::int32_t k = begin; k < end; ++k) accumulateBroadcast(g, k, px, py, nr2, srv, sr2, a);
  });
  sp.count = lowLane(a.count);
  sp.vel = Vec2{lowLane(a.vx), lowLane(a.vy)};
  sp.rel = Vec2{lowLane(a.rx), lowLane(a.ry)};
  sp.sep = Vec2{lowLane(a.sx), lowLane(a.sy)};
  sp.coincident = a.coincident[0];
  sq.count = highLane(a.count);
  sq.vel = Vec2{highLane(a.vx), highLane(a.vy)};
  sq.rel = Vec2{highLane(a.rx), highLane(a.ry)};
  sq.sep = Vec2{highLane(a.sx), highLane(a.sy)};
  sq.coincident = a.coincident[1];
#else
  sp = neighbourSums(g, p, nr, sr);
  sq = neighbourSums(g, q, nr, sr);
#endif
}

// The steering acceleration of `self` from its neighbour sums.
Vec2 steeringFrom(const FlockSettings& s, const NeighbourGrid& grid, NeighbourSums n,
                  const GridEntry& self, Vec2 goal, bool hasGoal) {
  if (n.coincident > 1) {
    // Exact overlaps besides the agent itself (rare): split them along x by id so that the
    // push is deterministic.
    grid.forEachNear(self.pos, s.neighbourRadius, [&](const GridEntry& o) {
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

}  // namespace

int Flock::useLanes(int lanes) {
  lanes_ = lanes >= 2 ? 2 : 1;
#if defined(ZONESIM_FLOCK_AVX)
  static const bool kAvx = __builtin_cpu_supports("avx");
  if (lanes >= 4 && kAvx) lanes_ = 4;
#endif
  return lanes_;
}

Vec2 Flock::steering(const GridEntry& self, Vec2 goal, bool hasGoal) const {
  const FlockSettings& s = settings_;
  return steeringFrom(s, grid_,
                      neighbourSums(grid_, self.pos, s.neighbourRadius, s.separationRadius), self,
                      goal, hasGoal);
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
  const FlockSettings& s = settings_;
  auto advance = [&](const GridEntry& e, Vec2 acc) {
    const double h = plan.empty() ? dt : plan.dt[e.src];
    Vec2 v = clampLength(e.vel + acc * h, s.maxSpeed);
    agents.vel[e.src] = v;
    agents.pos[e.src] = e.pos + v * h;
  };
  auto goalOf = [&](const GridEntry& e) { return hasGoal ? goalVel[e.src] : Vec2{}; };
  auto steerPair = [&](const GridEntry& a, const GridEntry& b) {
    NeighbourSums sa, sb;
    neighbourSumsPair(grid_, a.pos, b.pos, s.neighbourRadius, s.separationRadius, sa, sb);
    advance(a, steeringFrom(s, grid_, sa, a, goalOf(a), hasGoal));
    advance(b, steeringFrom(s, grid_, sb, b, goalOf(b), hasGoal));
  };
  // Four (AVX) or two (SSE2) agents per pass over the union of their neighbourhoods.
  auto steerQuad = [&](const GridEntry* const* q) {
#if defined(ZONESIM_FLOCK_AVX)
    if (lanes_ == 4) {
      const Vec2 p[4] = {q[0]->pos, q[1]->pos, q[2]->pos, q[3]->pos};
      std::int32_t ranges[2 * kQuadRows];
      int rows = grid_.rowRangesNearAll(p, 4, s.neighbourRadius, ranges, kQuadRows);
      if (rows >= 0) {
        QuadSums sums;
        neighbourSumsQuad(grid_, p, ranges, rows, s.neighbourRadius, s.separationRadius, sums);
        for (int l = 0; l < 4; ++l) {
          NeighbourSums n;
          n.count = sums.count[l];
          n.vel = Vec2{sums.vx[l], sums.vy[l]};
          n.rel = Vec2{sums.rx[l], sums.ry[l]};
          n.sep = Vec2{sums.sx[l], sums.sy[l]};
          n.coincident = sums.coincident[l];
          advance(*q[l], steeringFrom(s, grid_, n, *q[l], goalOf(*q[l]), hasGoal));
        }
        return;
      }
    }
#endif
    steerPair(*q[0], *q[1]);
    steerPair(*q[2], *q[3]);
  };
  // Owned agents in cell order: consecutive agents share most of their neighbour cells, so
  // the ones that steer go through the neighbour sums in groups.
  const GridEntry* waiting[4];
  int held = 0;
  for (const GridEntry& e : grid_.entries()) {
    if (e.src < 0) continue;
    const double h = plan.empty() ? dt : plan.dt[e.src];
    if (h <= 0.0) continue;
    if (!plan.empty() && !plan.steer[e.src]) {
      Vec2 acc;
      if (hasGoal) acc = clampLength((goalVel[e.src] - e.vel) * s.goalWeight, s.maxForce);
      advance(e, acc);
      continue;
    }
    if (lanes_ == 1) {
      advance(e, steering(e, goalOf(e), hasGoal));
      continue;
    }
    waiting[held++] = &e;
    if (held == 4) {
      steerQuad(waiting);
      held = 0;
    }
  }
  if (held >= 2) steerPair(*waiting[0], *waiting[1]);
  if (held == 3) advance(*waiting[2], steering(*waiting[2], goalOf(*waiting[2]), hasGoal));
  if (held == 1) advance(*waiting[0], steering(*waiting[0], goalOf(*waiting[0]), hasGoal));
}

}  // namespace zonesim::crowd
