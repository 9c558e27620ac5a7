#include "crowd/flock.h"

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

// Four (AVX) or eight (AVX-512) agents at once, one per vector lane, on the same scheme as
// PairLanes: each candidate of the union of the agents' rows is broadcast to every lane, so
// each lane is the sequential sum over its agent's in-range neighbours in canonical order.
// No FMA (the build is ISO C++, so GCC does not contract): every product is rounded before it
// is added, exactly as in the SSE2 loops, so the lanes are bitwise the one-agent sums. Chosen
// at run time; the target attributes keep the rest of the library baseline x86-64.
//
// Two passes over the candidates. The first adds the count, velocity and offset terms for
// every candidate without a branch and notes, in canonical order, the candidates closer than
// the separation radius to some lane (about one in five) and which lanes. The second adds the
// separation terms (a square root and two divisions) of the noted (candidate, lane) pairs
// only. A branch per candidate on "close to any lane" was taken at random and cost more than
// the arithmetic it skipped.
struct LaneSums {
  double count[8], vx[8], vy[8], rx[8], ry[8], sx[8], sy[8], coincident[8];
};

// Rows of the union of the discs, at most this many (else the caller takes two pairs).
constexpr int kGroupRows = 16;

// The separation terms of the noted pairs, four pairs per instruction: a noted candidate is
// close to 1.1 lanes on average, so the square root and divisions of a lane-wide pass per
// candidate (as the first pass does) went mostly to lanes that discard them; they took 40% of
// the neighbour sums. Each pair's term is the same correctly rounded operations as in the
// one-agent loops, and each lane subtracts its terms one after the other in canonical order
// (from +0, as the vector loops did): bitwise the lane-wide sums.
__attribute__((target("avx"))) void separationSums(const NeighbourGrid& g, const Vec2* p, double sr,
                                                   int close, NotedScratch& noted, LaneSums& out) {
  const double *xs = g.xs(), *ys = g.ys();
  double* dx = noted.dx.data();
  double* dy = noted.dy.data();
  std::uint8_t* lane = noted.lane.data();
  int pairs = 0;
  for (int c = 0; c < close; ++c) {
    const std::int32_t k = noted.k[c];
    for (unsigned m = noted.lanes[c]; m != 0; m &= m - 1) {
      const int l = __builtin_ctz(m);
      lane[pairs] = static_cast<std::uint8_t>(l);
      dx[pairs] = xs[k] - p[l].x;
      dy[pairs] = ys[k] - p[l].y;
      ++pairs;
    }
  }
  for (int j = pairs; j % 4 != 0; ++j) {  // whole vectors: pad with a harmless distance
    dx[j] = sr;
    dy[j] = 0.0;
  }
  const __m256d srv = _mm256_set1_pd(sr), one = _mm256_set1_pd(1.0);
  for (int j = 0; j < pairs; j += 4) {
    const __m256d x = _mm256_loadu_pd(dx + j), y = _mm256_loadu_pd(dy + j);
    const __m256d d = _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y)));
    const __m256d w = _mm256_div_pd(_mm256_sub_pd(_mm256_div_pd(srv, d), one), d);
    _mm256_storeu_pd(dx + j, _mm256_mul_pd(x, w));
    _mm256_storeu_pd(dy + j, _mm256_mul_pd(y, w));
  }
  double sx[8] = {}, sy[8] = {};
  for (int j = 0; j < pairs; ++j) {
    sx[lane[j]] -= dx[j];
    sy[lane[j]] -= dy[j];
  }
  for (int l = 0; l < 8; ++l) {
    out.sx[l] = sx[l];
    out.sy[l] = sy[l];
  }
}

__attribute__((target("avx"))) void neighbourSumsQuad(const NeighbourGrid& g, const Vec2* p,
                                                      const std::int32_t* ranges, int rows,
                                                      double nr, double sr, NotedScratch& noted,
                                                      LaneSums& out) {
  const __m256d px = _mm256_set_pd(p[3].x, p[2].x, p[1].x, p[0].x);
  const __m256d py = _mm256_set_pd(p[3].y, p[2].y, p[1].y, p[0].y);
  const __m256d nr2 = _mm256_set1_pd(nr * nr);
  const __m256d sr2 = _mm256_set1_pd(sr * sr), one = _mm256_set1_pd(1.0);
  const __m256d tiny = _mm256_set1_pd(1e-18);
  __m256d count = _mm256_setzero_pd(), vx = _mm256_setzero_pd(), vy = _mm256_setzero_pd();
  __m256d rx = _mm256_setzero_pd(), ry = _mm256_setzero_pd(), coin = _mm256_setzero_pd();
  const double *xs = g.xs(), *ys = g.ys(), *vxs = g.vxs(), *vys = g.vys();
  int close = 0;
  for (int r = 0; r < rows; ++r) {
    for (std::int32_t k = ranges[2 * r]; k < ranges[2 * r + 1]; ++k) {
      __m256d dx = _mm256_sub_pd(_mm256_broadcast_sd(xs + k), px);
      __m256d dy = _mm256_sub_pd(_mm256_broadcast_sd(ys + k), py);
      __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
      __m256d in = _mm256_cmp_pd(d2, nr2, _CMP_LT_OQ);
      count = _mm256_add_pd(count, _mm256_and_pd(in, one));
      vx = _mm256_add_pd(vx, _mm256_and_pd(in, _mm256_broadcast_sd(vxs + k)));
      vy = _mm256_add_pd(vy, _mm256_and_pd(in, _mm256_broadcast_sd(vys + k)));
      rx = _mm256_add_pd(rx, _mm256_and_pd(in, dx));
      ry = _mm256_add_pd(ry, _mm256_and_pd(in, dy));
      __m256d near = _mm256_cmp_pd(d2, sr2, _CMP_LT_OQ);
      __m256d zero = _mm256_and_pd(near, _mm256_cmp_pd(d2, tiny, _CMP_LE_OQ));
      coin = _mm256_add_pd(coin, _mm256_and_pd(zero, one));
      const int pushed = _mm256_movemask_pd(_mm256_andnot_pd(zero, near));
      noted.k[close] = k;
      noted.lanes[close] = static_cast<std::uint8_t>(pushed);
      close += pushed != 0;
    }
  }
  _mm256_storeu_pd(out.count, count);
  _mm256_storeu_pd(out.vx, vx);
  _mm256_storeu_pd(out.vy, vy);
  _mm256_storeu_pd(out.rx, rx);
  _mm256_storeu_pd(out.ry, ry);
  _mm256_storeu_pd(out.coincident, coin);
  separationSums(g, p, sr, close, noted, out);
}

// The eight-lane version. Masked adds leave a lane's sum as it was where the AVX loop adds an
// exact zero: the same value, since a sum that starts at +0 is never -0.
__attribute__((target("avx512f"))) void neighbourSumsOcta(const NeighbourGrid& g, const Vec2* p,
                                                          const std::int32_t* ranges, int rows,
                                                          double nr, double sr, NotedScratch& noted,
                                                          LaneSums& out) {
  const __m512d px = _mm512_set_pd(p[7].x, p[6].x, p[5].x, p[4].x, p[3].x, p[2].x, p[1].x, p[0].x);
  const __m512d py = _mm512_set_pd(p[7].y, p[6].y, p[5].y, p[4].y, p[3].y, p[2].y, p[1].y, p[0].y);
  const __m512d nr2 = _mm512_set1_pd(nr * nr);
  const __m512d sr2 = _mm512_set1_pd(sr * sr), one = _mm512_set1_pd(1.0);
  const __m512d tiny = _mm512_set1_pd(1e-18);
  __m512d count = _mm512_setzero_pd(), vx = _mm512_setzero_pd(), vy = _mm512_setzero_pd();
  __m512d rx = _mm512_setzero_pd(), ry = _mm512_setzero_pd(), coin = _mm512_setzero_pd();
  const double *xs = g.xs(), *ys = g.ys(), *vxs = g.vxs(), *vys = g.vys();
  int close = 0;
  for (int r = 0; r < rows; ++r) {
    for (std::int32_t k = ranges[2 * r]; k < ranges[2 * r + 1]; ++k) {
      __m512d dx = _mm512_sub_pd(_mm512_set1_pd(xs[k]), px);
      __m512d dy = _mm512_sub_pd(_mm512_set1_pd(ys[k]), py);
      __m512d d2 = _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy));
      __mmask8 in = _mm512_cmp_pd_mask(d2, nr2, _CMP_LT_OQ);
      count = _mm512_mask_add_pd(count, in, count, one);
      vx = _mm512_mask_add_pd(vx, in, vx, _mm512_set1_pd(vxs[k]));
      vy = _mm512_mask_add_pd(vy, in, vy, _mm512_set1_pd(vys[k]));
      rx = _mm512_mask_add_pd(rx, in, rx, dx);
      ry = _mm512_mask_add_pd(ry, in, ry, dy);
      __mmask8 near = _mm512_cmp_pd_mask(d2, sr2, _CMP_LT_OQ);
      __mmask8 zero = _mm512_mask_cmp_pd_mask(near, d2, tiny, _CMP_LE_OQ);
      coin = _mm512_mask_add_pd(coin, zero, coin, one);
      const __mmask8 pushed = near & ~zero;
      noted.k[close] = k;
      noted.lanes[close] = pushed;
      close += pushed != 0;
    }
  }
  _mm512_storeu_pd(out.count, count);
  _mm512_storeu_pd(out.vx, vx);
  _mm512_storeu_pd(out.vy, vy);
  _mm512_storeu_pd(out.rx, rx);
  _mm512_storeu_pd(out.ry, ry);
  _mm512_storeu_pd(out.coincident, coin);
  separationSums(g, p, sr, close, noted, out);
}

// What the lane-wide path needs of each agent of a group, and what it gives back.
struct LaneAgents {
  double vx[8], vy[8];    // velocity at the start of the step
  double px[8], py[8];    // position at the start of the step
  double gx[8], gy[8];    // goal velocity (unused without goals)
  double h[8];            // the agent's dt
  double ax[8], ay[8];    // out: steering acceleration
  double nvx[8], nvy[8];  // out: new velocity (without bodies)
  double npx[8], npy[8];  // out: new position (without bodies)
};

// `v` shortened to at most `max_len`, four lanes: clampLength's operations, with both of its
// outcomes computed and the one it returns kept (none computed when every lane keeps `v`).
__attribute__((target("avx"))) inline void clampLengthFour(__m256d& x, __m256d& y, double max_len) {
  const __m256d l2 = _mm256_add_pd(_mm256_mul_pd(x, x), _mm256_mul_pd(y, y));
  const __m256d keep = _mm256_cmp_pd(l2, _mm256_set1_pd(max_len * max_len), _CMP_LE_OQ);
  if (_mm256_movemask_pd(keep) == 0xf) return;
  const __m256d f = _mm256_div_pd(_mm256_set1_pd(max_len), _mm256_sqrt_pd(l2));
  x = _mm256_blendv_pd(_mm256_mul_pd(x, f), x, keep);
  y = _mm256_blendv_pd(_mm256_mul_pd(y, f), y, keep);
}

// steeringFrom and the step's move (semi-implicit Euler, no bodies) for lanes [first,
// first + 4) of a group, with the same operations in the same order, each correctly rounded
// (no FMA), so every lane is bitwise the one-agent code. The scalar code ran one agent's
// chain of a division, two square roots and three more divisions at a time, a sixth of the
// step; four lanes share each instruction. Lanes with exact overlaps (coincident > 1) are
// redone by the caller.
__attribute__((target("avx"))) void steerAndMoveFour(const FlockSettings& s, const LaneSums& n,
                                                     bool has_goal, int first, LaneAgents& a) {
  const __m256d one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
  const __m256d vx = _mm256_loadu_pd(a.vx + first), vy = _mm256_loadu_pd(a.vy + first);
  const __m256d sw = _mm256_set1_pd(s.separation_weight);
  __m256d ax = _mm256_mul_pd(_mm256_loadu_pd(n.sx + first), sw);
  __m256d ay = _mm256_mul_pd(_mm256_loadu_pd(n.sy + first), sw);
  // The agent itself is counted once: count - 1 is exact (a small whole number).
  const __m256d count = _mm256_sub_pd(_mm256_loadu_pd(n.count + first), one);
  const __m256d some = _mm256_cmp_pd(count, zero, _CMP_GT_OQ);
  const __m256d inv = _mm256_div_pd(one, _mm256_blendv_pd(one, count, some));
  const __m256d aw = _mm256_set1_pd(s.alignment_weight);
  __m256d tx = _mm256_add_pd(
      ax,
      _mm256_mul_pd(
          _mm256_sub_pd(_mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(n.vx + first), vx), inv), vx),
          aw));
  __m256d ty = _mm256_add_pd(
      ay,
      _mm256_mul_pd(
          _mm256_sub_pd(_mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(n.vy + first), vy), inv), vy),
          aw));
  const __m256d cw = _mm256_mul_pd(inv, _mm256_set1_pd(s.cohesion_weight));
  tx = _mm256_add_pd(tx, _mm256_mul_pd(_mm256_loadu_pd(n.rx + first), cw));
  ty = _mm256_add_pd(ty, _mm256_mul_pd(_mm256_loadu_pd(n.ry + first), cw));
  ax = _mm256_blendv_pd(ax, tx, some);
  ay = _mm256_blendv_pd(ay, ty, some);
  if (has_goal) {
    const __m256d gw = _mm256_set1_pd(s.goal_weight);
    ax = _mm256_add_pd(ax, _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(a.gx + first), vx), gw));
    ay = _mm256_add_pd(ay, _mm256_mul_pd(_mm256_sub_pd(_mm256_loadu_pd(a.gy + first), vy), gw));
  }
  clampLengthFour(ax, ay, s.max_force);
  _mm256_storeu_pd(a.ax + first, ax);
  _mm256_storeu_pd(a.ay + first, ay);
  const __m256d h = _mm256_loadu_pd(a.h + first);
  __m256d nvx = _mm256_add_pd(vx, _mm256_mul_pd(ax, h));
  __m256d nvy = _mm256_add_pd(vy, _mm256_mul_pd(ay, h));
  clampLengthFour(nvx, nvy, s.max_speed);
  _mm256_storeu_pd(a.nvx + first, nvx);
  _mm256_storeu_pd(a.nvy + first, nvy);
  _mm256_storeu_pd(a.npx + first,
                   _mm256_add_pd(_mm256_loadu_pd(a.px + first), _mm256_mul_pd(nvx, h)));
  _mm256_storeu_pd(a.npy + first,
                   _mm256_add_pd(_mm256_loadu_pd(a.py + first), _mm256_mul_pd(nvy, h)));
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
Vec2 steeringFrom(const FlockSettings& s, const NeighbourGrid& grid, const NeighbourSums& n,
                  const GridEntry& self, Vec2 goal, bool hasGoal) {
  Vec2 sep = n.sep;
  if (n.coincident > 1) {
    // Exact overlaps besides the agent itself (rare): split them along x by id so that the
    // push is deterministic.
    grid.forEachNear(self.pos, s.neighbour_radius, [&](const GridEntry& o) {
      if (o.id != self.id && lengthSq(o.pos - self.pos) <= 1e-18)
        sep.x += self.id < o.id ? -1e3 : 1e3;
    });
  }
  // Take out the agent itself: counted once, with its own velocity; its offset is zero.
  int count = int(n.count) - 1;
  Vec2 acc = sep * s.separation_weight;
  if (count > 0) {
    double inv = 1.0 / count;
    acc += ((n.vel - self.vel) * inv - self.vel) * s.alignment_weight;
    acc += n.rel * (inv * s.cohesion_weight);
  }
  if (hasGoal) acc += (goal - self.vel) * s.goal_weight;
  return clampLength(acc, s.max_force);
}

}  // namespace

int Flock::useLanes(int lanes) {
  lanes_ = lanes >= 2 ? 2 : 1;
#if defined(ZONESIM_FLOCK_AVX)
  static const bool kAvx = __builtin_cpu_supports("avx");
  static const bool kAvx512 = __builtin_cpu_supports("avx512f");
  if (lanes >= 4 && kAvx) lanes_ = 4;
  if (lanes >= 8 && kAvx512) lanes_ = 8;
#endif
  return lanes_;
}

Vec2 Flock::steering(const GridEntry& self, Vec2 goal, bool hasGoal) const {
  const FlockSettings& s = settings_;
  return steeringFrom(s, grid_,
                      neighbourSums(grid_, self.pos, s.neighbour_radius, s.separation_radius), self,
                      goal, hasGoal);
}

Flock::Flock(const FlockSettings& settings) : settings_(settings) {
  if (!(settings.body_radius >= 0.0))
    throw std::invalid_argument("Flock: body_radius must be at least 0");
  if (settings.body_radius > 0.0 && !(settings.sight > 2.0 * settings.body_radius))
    throw std::invalid_argument("Flock: sight must exceed twice body_radius");
  useLanes(8);
}

void Flock::step(const AgentSpan& agents, const GhostSpan& ghosts, double dt,
                 std::span<const Vec2> goal_vel, const StepPlan& plan) {
  const std::size_t n = agents.size();
  if (agents.pos.size() != n || agents.vel.size() != n || ghosts.pos.size() != ghosts.size() ||
      ghosts.vel.size() != ghosts.size() || (!goal_vel.empty() && goal_vel.size() != n) ||
      (!plan.empty() && (plan.dt.size() != n || plan.steer.size() != n)))
    throw std::invalid_argument("Flock::step: array sizes differ");
  grid_.build(agents, ghosts, settings_.neighbour_radius);
  const bool hasGoal = !goal_vel.empty();
  const FlockSettings& s = settings_;
  const std::span<const GridEntry> entries = grid_.entries();
  auto advance = [&](const GridEntry& e, Vec2 acc) {
    const double h = plan.empty() ? dt : plan.dt[e.src];
    Vec2 v = clampLength(e.vel + acc * h, s.max_speed);
    Vec2 x = v * h;
    if (s.body_radius > 0.0 && (plan.empty() || plan.steer[e.src])) {
      keep_apart_.begin(s.body_radius, std::min(s.max_speed * h, 0.5 * s.sight - s.body_radius));
      gatherGaps(grid_, std::int32_t(&e - entries.data()), keep_apart_);
      const Vec2 kept = keep_apart_.move(x);
      if (!(kept == x)) {
        x = kept;
        v = x * (1.0 / h);
      }
    }
    agents.vel[e.src] = v;
    agents.pos[e.src] = e.pos + x;
  };
  auto goalOf = [&](const GridEntry& e) { return hasGoal ? goal_vel[e.src] : Vec2{}; };
  auto steerPair = [&](const GridEntry& a, const GridEntry& b) {
    NeighbourSums sa, sb;
    neighbourSumsPair(grid_, a.pos, b.pos, s.neighbour_radius, s.separation_radius, sa, sb);
    advance(a, steeringFrom(s, grid_, sa, a, goalOf(a), hasGoal));
    advance(b, steeringFrom(s, grid_, sb, b, goalOf(b), hasGoal));
  };
  // Up to eight (AVX-512), four (AVX) or two (SSE2) agents per pass over the union of their
  // neighbourhoods; `q[0 .. held)` lie in one row of cells.
  auto steerGroup = [&](const GridEntry* const* q, int held) {
#if defined(ZONESIM_FLOCK_AVX)
    if (lanes_ >= 4) {
      // Unused lanes repeat the last agent: the union of the discs stays the same.
      Vec2 p[8];
      for (int l = 0; l < lanes_; ++l) p[l] = q[l < held ? l : held - 1]->pos;
      std::int32_t ranges[2 * kGroupRows];
      int rows = grid_.rowRangesNearBox(p, lanes_, s.neighbour_radius, ranges, kGroupRows);
      if (rows >= 0) {
        std::size_t candidates = 0;
        for (int r = 0; r < rows; ++r) candidates += std::size_t(ranges[2 * r + 1] - ranges[2 * r]);
        noted_.reserve(candidates);
        LaneSums sums;
        if (lanes_ == 8)
          neighbourSumsOcta(grid_, p, ranges, rows, s.neighbour_radius, s.separation_radius, noted_,
                            sums);
        else
          neighbourSumsQuad(grid_, p, ranges, rows, s.neighbour_radius, s.separation_radius, noted_,
                            sums);
        LaneAgents la;
        for (int l = 0; l < lanes_; ++l) {
          const GridEntry& e = *q[l < held ? l : held - 1];
          la.vx[l] = e.vel.x;
          la.vy[l] = e.vel.y;
          la.px[l] = e.pos.x;
          la.py[l] = e.pos.y;
          const Vec2 goal = goalOf(e);
          la.gx[l] = goal.x;
          la.gy[l] = goal.y;
          la.h[l] = plan.empty() ? dt : plan.dt[e.src];
        }
        for (int first = 0; first < held; first += 4) steerAndMoveFour(s, sums, hasGoal, first, la);
        for (int l = 0; l < held; ++l) {
          const GridEntry& e = *q[l];
          if (sums.coincident[l] > 1) {  // exact overlaps: split by id (rare)
            NeighbourSums n;
            n.count = sums.count[l];
            n.vel = Vec2{sums.vx[l], sums.vy[l]};
            n.rel = Vec2{sums.rx[l], sums.ry[l]};
            n.sep = Vec2{sums.sx[l], sums.sy[l]};
            n.coincident = int(sums.coincident[l]);
            advance(e, steeringFrom(s, grid_, n, e, goalOf(e), hasGoal));
          } else if (s.body_radius > 0.0) {
            advance(e, Vec2{la.ax[l], la.ay[l]});
          } else {
            agents.vel[e.src] = Vec2{la.nvx[l], la.nvy[l]};
            agents.pos[e.src] = Vec2{la.npx[l], la.npy[l]};
          }
        }
        return;
      }
    }
#endif
    int l = 0;
    for (; l + 2 <= held; l += 2) steerPair(*q[l], *q[l + 1]);
    if (l < held) advance(*q[l], steering(*q[l], goalOf(*q[l]), hasGoal));
  };
  // Owned agents in cell order: consecutive agents share most of their neighbour cells, so
  // the ones that steer go through the neighbour sums in groups. A group ends with its row of
  // cells: the union of discs on either side of a row's end would span the whole width.
  const GridEntry* waiting[8];
  int held = 0;
  std::int32_t heldRow = -1;
  const int group = lanes_ == 1 ? 1 : (lanes_ == 2 ? 4 : lanes_);
  for (const GridEntry& e : grid_.entries()) {
    if (e.src < 0) continue;
    const double h = plan.empty() ? dt : plan.dt[e.src];
    if (h <= 0.0) continue;
    if (!plan.empty() && !plan.steer[e.src]) {
      Vec2 acc;
      if (hasGoal) acc = clampLength((goal_vel[e.src] - e.vel) * s.goal_weight, s.max_force);
      advance(e, acc);
      continue;
    }
    if (lanes_ == 1) {
      advance(e, steering(e, goalOf(e), hasGoal));
      continue;
    }
    const std::int32_t row = grid_.rowOf(e.cell);
    if (held > 0 && row != heldRow) {
      steerGroup(waiting, held);
      held = 0;
    }
    heldRow = row;
    // The agent is written back after its group's sums: fetch its lines meanwhile (in random
    // storage order each write is a cache miss, and they filled the store buffer).
    __builtin_prefetch(&agents.pos[e.src], 1);
    __builtin_prefetch(&agents.vel[e.src], 1);
    waiting[held++] = &e;
    if (held == group) {
      steerGroup(waiting, held);
      held = 0;
    }
  }
  if (held > 0) steerGroup(waiting, held);
}

}  // namespace zonesim::crowd
