// The wide contact solver's passes, one template over the lane count W: 1 (the scalar
// reference), 4 (SSE2, any x86-64) and 8 (AVX2, chosen at run time). Each lane carries out the
// same float operations in the same order whatever W is: GCC vector extensions only add, multiply,
// divide, compare and select lane by lane, square roots are taken one lane at a time, and the
// file is compiled with -ffp-contract=off (no fused multiply-adds in one width and not another).
// With the width-independent layout of constraint_colouring.h, every width ends bitwise equal.

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "physics/wide_contact_block.h"

namespace zonesim::physics::wide {
namespace {

#define ZONESIM_WIDE_INLINE inline __attribute__((always_inline))

// One vector type per width, spelled out: GCC drops vector_size on a dependent typedef.
template <int W>
struct Simd;
template <>
struct Simd<1> {
  typedef float F __attribute__((vector_size(4)));
};
template <>
struct Simd<4> {
  typedef float F __attribute__((vector_size(16)));
};
template <>
struct Simd<8> {
  typedef float F __attribute__((vector_size(32)));
};
static_assert(sizeof(Simd<8>::F) == 8 * sizeof(float));
// gather and scatter move whole records: linear xyz, angular xyz, 2 unused floats.
static_assert(sizeof(SolverMotion) == 8 * sizeof(float) &&
              offsetof(SolverMotion, angular) == 3 * sizeof(float));

template <class F>
struct V3 {
  F x, y, z;
};

template <class F>
ZONESIM_WIDE_INLINE F load(const float* p) {
  F v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

template <class F>
ZONESIM_WIDE_INLINE void store(float* p, F v) {
  std::memcpy(p, &v, sizeof v);
}

template <class F>
ZONESIM_WIDE_INLINE F splat(float x) {
  return F{} + x;
}

template <class F>
ZONESIM_WIDE_INLINE V3<F> load3(const Lanes* p, int o) {
  return {load<F>(p[0] + o), load<F>(p[1] + o), load<F>(p[2] + o)};
}

// As std::max and std::min, lane by lane (the same answer for signed zeros).
template <class F>
ZONESIM_WIDE_INLINE F vmax(F a, F b) {
  return a < b ? b : a;
}

template <class F>
ZONESIM_WIDE_INLINE F dot(const V3<F>& a, const V3<F>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <class F>
ZONESIM_WIDE_INLINE V3<F> cross(const V3<F>& a, const V3<F>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <class F>
ZONESIM_WIDE_INLINE V3<F> operator+(const V3<F>& a, const V3<F>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}

template <class F>
ZONESIM_WIDE_INLINE V3<F> operator-(const V3<F>& a, const V3<F>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}

template <class F>
ZONESIM_WIDE_INLINE V3<F> operator*(F s, const V3<F>& a) {
  return {s * a.x, s * a.y, s * a.z};
}

// A symmetric 3x3 matrix (xx yy zz xy xz yz) times v.
template <class F>
ZONESIM_WIDE_INLINE V3<F> symmetricTimes(const F* m, const V3<F>& v) {
  return {m[0] * v.x + m[3] * v.y + m[4] * v.z, m[3] * v.x + m[1] * v.y + m[5] * v.z,
          m[4] * v.x + m[5] * v.y + m[2] * v.z};
}

#if defined(__x86_64__) && defined(__GNUC__)
#define ZONESIM_WIDE_AVX2 1
#define ZONESIM_WIDE_TARGET_AVX2 __attribute__((target("avx2")))

// 8 lanes: loads the 8 records (linear xyz, angular xyz, 2 unused) whole and transposes them in
// registers (unpack pairs, shuffle quads, swap halves, as Box2D's b2GatherBodies), instead of
// 48 scalar stores and 6 vector loads of the same bytes, which the CPU cannot forward. Not
// always_inline: GCC refuses that into the generic templates, but inlines it into the AVX2
// functions that end up calling it.
ZONESIM_WIDE_TARGET_AVX2 inline void gather8(const SolverMotion* m, const std::uint32_t* slot,
                                             __m256* columns) {
  __m256 r[8];
  for (int l = 0; l < 8; ++l) r[l] = _mm256_load_ps(m[slot[l]].linear);
  const __m256 t0 = _mm256_unpacklo_ps(r[0], r[1]), t1 = _mm256_unpackhi_ps(r[0], r[1]);
  const __m256 t2 = _mm256_unpacklo_ps(r[2], r[3]), t3 = _mm256_unpackhi_ps(r[2], r[3]);
  const __m256 t4 = _mm256_unpacklo_ps(r[4], r[5]), t5 = _mm256_unpackhi_ps(r[4], r[5]);
  const __m256 t6 = _mm256_unpacklo_ps(r[6], r[7]), t7 = _mm256_unpackhi_ps(r[6], r[7]);
  const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xee);
  const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xee);
  const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xee);
  const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xee);
  columns[0] = _mm256_permute2f128_ps(u0, u4, 0x20);  // linear x
  columns[1] = _mm256_permute2f128_ps(u1, u5, 0x20);
  columns[2] = _mm256_permute2f128_ps(u2, u6, 0x20);
  columns[3] = _mm256_permute2f128_ps(u3, u7, 0x20);  // angular x
  columns[4] = _mm256_permute2f128_ps(u0, u4, 0x31);
  columns[5] = _mm256_permute2f128_ps(u1, u5, 0x31);
}

// Square roots of 8 lanes: IEEE square roots are correctly rounded, so every lane gets the bits
// std::sqrt gives it at any width. Not always_inline, as gather8.
ZONESIM_WIDE_TARGET_AVX2 inline __m256 sqrt8(__m256 x) {
  return _mm256_sqrt_ps(x);
}

// The inverse: 6 columns back into 8 whole records (the unused floats written zero, as they
// are). Lanes write distinct bodies but for the sink, which nothing reads.
ZONESIM_WIDE_TARGET_AVX2 inline void scatter8(SolverMotion* m, const std::uint32_t* slot,
                                              const __m256* c) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256 t0 = _mm256_unpacklo_ps(c[0], c[1]), t1 = _mm256_unpackhi_ps(c[0], c[1]);
  const __m256 t2 = _mm256_unpacklo_ps(c[2], c[3]), t3 = _mm256_unpackhi_ps(c[2], c[3]);
  const __m256 t4 = _mm256_unpacklo_ps(c[4], c[5]), t5 = _mm256_unpackhi_ps(c[4], c[5]);
  const __m256 t6 = _mm256_unpacklo_ps(zero, zero), t7 = t6;
  const __m256 u0 = _mm256_shuffle_ps(t0, t2, 0x44), u1 = _mm256_shuffle_ps(t0, t2, 0xee);
  const __m256 u2 = _mm256_shuffle_ps(t1, t3, 0x44), u3 = _mm256_shuffle_ps(t1, t3, 0xee);
  const __m256 u4 = _mm256_shuffle_ps(t4, t6, 0x44), u5 = _mm256_shuffle_ps(t4, t6, 0xee);
  const __m256 u6 = _mm256_shuffle_ps(t5, t7, 0x44), u7 = _mm256_shuffle_ps(t5, t7, 0xee);
  const __m256 r[8] = {_mm256_permute2f128_ps(u0, u4, 0x20), _mm256_permute2f128_ps(u1, u5, 0x20),
                       _mm256_permute2f128_ps(u2, u6, 0x20), _mm256_permute2f128_ps(u3, u7, 0x20),
                       _mm256_permute2f128_ps(u0, u4, 0x31), _mm256_permute2f128_ps(u1, u5, 0x31),
                       _mm256_permute2f128_ps(u2, u6, 0x31), _mm256_permute2f128_ps(u3, u7, 0x31)};
  for (int l = 0; l < 8; ++l) _mm256_store_ps(m[slot[l]].linear, r[l]);
}
#endif

// Six register columns (linear xyz, angular xyz) as the lanes' motions: a bit cast, no lane moves.
template <class F, class C>
ZONESIM_WIDE_INLINE void fromColumns(const C (&c)[6], V3<F>& lin, V3<F>& ang) {
  lin = {std::bit_cast<F>(c[0]), std::bit_cast<F>(c[1]), std::bit_cast<F>(c[2])};
  ang = {std::bit_cast<F>(c[3]), std::bit_cast<F>(c[4]), std::bit_cast<F>(c[5])};
}

// The lanes' bodies' motions as vectors: 8 and 4 lanes move whole records through registers
// (pure data movement, so every width still sees the same bits), 1 lane goes through memory.
template <int W>
ZONESIM_WIDE_INLINE void gather(const SolverMotion* m, const std::uint32_t* slot,
                                V3<typename Simd<W>::F>& lin, V3<typename Simd<W>::F>& ang) {
  using F = typename Simd<W>::F;
#if defined(ZONESIM_WIDE_AVX2)
  if constexpr (W == 8) {
    __m256 c[6];
    gather8(m, slot, c);
    fromColumns(c, lin, ang);
    return;
  }
#endif
#if defined(__SSE2__)
  if constexpr (W == 4) {
    // Each record as two quads: (linear xyz, angular x) and (angular yz, unused).
    __m128 a0 = _mm_load_ps(m[slot[0]].linear), a1 = _mm_load_ps(m[slot[1]].linear);
    __m128 a2 = _mm_load_ps(m[slot[2]].linear), a3 = _mm_load_ps(m[slot[3]].linear);
    __m128 b0 = _mm_load_ps(m[slot[0]].linear + 4), b1 = _mm_load_ps(m[slot[1]].linear + 4);
    __m128 b2 = _mm_load_ps(m[slot[2]].linear + 4), b3 = _mm_load_ps(m[slot[3]].linear + 4);
    _MM_TRANSPOSE4_PS(a0, a1, a2, a3);
    _MM_TRANSPOSE4_PS(b0, b1, b2, b3);
    const __m128 c[6] = {a0, a1, a2, a3, b0, b1};
    fromColumns(c, lin, ang);
    return;
  }
#endif
  {
    alignas(32) float part[6][W];
    for (int l = 0; l < W; ++l) {
      const SolverMotion& s = m[slot[l]];
      for (int k = 0; k < 3; ++k) {
        part[k][l] = s.linear[k];
        part[3 + k][l] = s.angular[k];
      }
    }
    lin = {load<F>(part[0]), load<F>(part[1]), load<F>(part[2])};
    ang = {load<F>(part[3]), load<F>(part[4]), load<F>(part[5])};
  }
}

template <int W>
ZONESIM_WIDE_INLINE void scatter(SolverMotion* m, const std::uint32_t* slot,
                                 const V3<typename Simd<W>::F>& lin,
                                 const V3<typename Simd<W>::F>& ang) {
  using F = typename Simd<W>::F;
  const F f[6] = {lin.x, lin.y, lin.z, ang.x, ang.y, ang.z};
#if defined(ZONESIM_WIDE_AVX2)
  if constexpr (W == 8) {
    __m256 c[6];
    std::memcpy(c, f, sizeof c);
    scatter8(m, slot, c);
    return;
  }
#endif
#if defined(__SSE2__)
  if constexpr (W == 4) {
    __m128 c[6];
    std::memcpy(c, f, sizeof c);
    __m128 a0 = c[0], a1 = c[1], a2 = c[2], a3 = c[3];
    __m128 b0 = c[4], b1 = c[5], b2 = _mm_setzero_ps(), b3 = _mm_setzero_ps();
    _MM_TRANSPOSE4_PS(a0, a1, a2, a3);
    _MM_TRANSPOSE4_PS(b0, b1, b2, b3);
    _mm_store_ps(m[slot[0]].linear, a0);
    _mm_store_ps(m[slot[0]].linear + 4, b0);
    _mm_store_ps(m[slot[1]].linear, a1);
    _mm_store_ps(m[slot[1]].linear + 4, b1);
    _mm_store_ps(m[slot[2]].linear, a2);
    _mm_store_ps(m[slot[2]].linear + 4, b2);
    _mm_store_ps(m[slot[3]].linear, a3);
    _mm_store_ps(m[slot[3]].linear + 4, b3);
    return;
  }
#endif
  {
    alignas(32) float part[6][W];
    for (int k = 0; k < 6; ++k) store(part[k], f[k]);
    for (int l = 0; l < W; ++l) {
      SolverMotion& s = m[slot[l]];
      for (int k = 0; k < 3; ++k) {
        s.linear[k] = part[k][l];
        s.angular[k] = part[3 + k][l];
      }
    }
  }
}

// Lane-wise square root, the same bits at every width (see sqrt8).
template <int W>
ZONESIM_WIDE_INLINE typename Simd<W>::F vsqrt(typename Simd<W>::F x) {
  using F = typename Simd<W>::F;
#if defined(ZONESIM_WIDE_AVX2)
  if constexpr (W == 8) return std::bit_cast<F>(sqrt8(std::bit_cast<__m256>(x)));
#endif
#if defined(__SSE2__)
  if constexpr (W == 4) return std::bit_cast<F>(_mm_sqrt_ps(std::bit_cast<__m128>(x)));
#endif
  F r;
  for (int l = 0; l < W; ++l) r[l] = std::sqrt(x[l]);
  return r;
}

// The velocities of one block's lanes o .. o+W, with the bodies' masses.
template <int W>
struct Pair {
  using F = typename Simd<W>::F;
  V3<F> va, wa, vb, wb;
  F ma, mb;
  F ia[6], ib[6];

  ZONESIM_WIDE_INLINE Pair(const BlockLanes& b, int o, const SolverBodies& bodies) {
    gather<W>(bodies.velocity.data(), b.read_a + o, va, wa);
    gather<W>(bodies.velocity.data(), b.read_b + o, vb, wb);
    ma = load<F>(b.inv_mass_a + o);
    mb = load<F>(b.inv_mass_b + o);
    for (int k = 0; k < 6; ++k) {
      ia[k] = load<F>(b.inv_inertia_a[k] + o);
      ib[k] = load<F>(b.inv_inertia_b[k] + o);
    }
  }
  ZONESIM_WIDE_INLINE void write(const BlockLanes& b, int o, SolverBodies& bodies) const {
    scatter<W>(bodies.velocity.data(), b.write_a + o, va, wa);
    scatter<W>(bodies.velocity.data(), b.write_b + o, vb, wb);
  }
  // Impulse p at anchors ra, rb: -p on body a, +p on body b.
  ZONESIM_WIDE_INLINE void apply(const V3<F>& ra, const V3<F>& rb, const V3<F>& p) {
    va = va - ma * p;
    wa = wa - symmetricTimes(ia, cross(ra, p));
    vb = vb + mb * p;
    wb = wb + symmetricTimes(ib, cross(rb, p));
  }
  // Normal impulse lambda along n, with the normal row's precomputed angular images.
  ZONESIM_WIDE_INLINE void applyNormal(const V3<F>& n, const V3<F>& ia_ca, const V3<F>& ib_cb,
                                       F lambda) {
    va = va - (ma * lambda) * n;
    wa = wa - lambda * ia_ca;
    vb = vb + (mb * lambda) * n;
    wb = wb + lambda * ib_cb;
  }
  ZONESIM_WIDE_INLINE F normalVelocity(const V3<F>& n, const V3<F>& ca, const V3<F>& cb) const {
    return dot(n, vb - va) + dot(cb, wb) - dot(ca, wa);
  }
};

// A point's normal row: the angular Jacobians ra x n, rb x n and their images under the inverse
// inertias, computed from the anchors wherever they are needed (wide_contact_block.h).
template <class F>
struct NormalRow {
  V3<F> ca, cb, ia_ca, ib_cb;
  ZONESIM_WIDE_INLINE NormalRow(const V3<F>& ra, const V3<F>& rb, const V3<F>& n, const F* ia,
                                const F* ib)
      : ca(cross(ra, n)),
        cb(cross(rb, n)),
        ia_ca(symmetricTimes(ia, ca)),
        ib_cb(symmetricTimes(ib, cb)) {}
};

// 1 / inv where inv > 0 and the point is used, else 0 (the quotients of other lanes are
// discarded).
template <class F, class M>
ZONESIM_WIDE_INLINE F massOf(F inv, M used) {
  const F zero = splat<F>(0.0f);
  return (used & (inv > zero)) ? splat<F>(1.0f) / inv : zero;
}

template <int W>
ZONESIM_WIDE_INLINE void buildRowsLanes(BlockLanes& b, int o) {
  using F = typename Simd<W>::F;
  const V3<F> n = load3<F>(b.normal, o);
  const V3<F> t[2] = {load3<F>(b.tangent[0], o), load3<F>(b.tangent[1], o)};
  const F masses = load<F>(b.inv_mass_a + o) + load<F>(b.inv_mass_b + o);
  F ia[6], ib[6];
  for (int k = 0; k < 6; ++k) {
    ia[k] = load<F>(b.inv_inertia_a[k] + o);
    ib[k] = load<F>(b.inv_inertia_b[k] + o);
  }
  const F count = load<F>(b.point_count + o);
  for (int i = 0; i < b.points; ++i) {
    PointLanes& p = b.point[i];
    const auto used = splat<F>(static_cast<float>(i)) < count;
    const V3<F> ra = load3<F>(p.ra, o), rb = load3<F>(p.rb, o);
    const NormalRow<F> row(ra, rb, n, ia, ib);
    store(p.normal_mass + o,
          massOf(masses + dot(row.ca, row.ia_ca) + dot(row.cb, row.ib_cb), used));
    for (int d = 0; d < 2; ++d) {
      const V3<F> ta = cross(ra, t[d]), tb = cross(rb, t[d]);
      const F inv = masses + dot(ta, symmetricTimes(ia, ta)) + dot(tb, symmetricTimes(ib, tb));
      store(p.tangent_mass[d] + o, massOf(inv, used));
    }
  }
}

template <int W>
ZONESIM_WIDE_INLINE void warmStartLanes(const BlockLanes& b, int o, SolverBodies& bodies) {
  using F = typename Simd<W>::F;
  Pair<W> v(b, o, bodies);
  const V3<F> n = load3<F>(b.normal, o), t0 = load3<F>(b.tangent[0], o);
  const V3<F> t1 = load3<F>(b.tangent[1], o);
  for (int i = 0; i < b.points; ++i) {
    const PointLanes& p = b.point[i];
    const V3<F> impulse = load<F>(p.normal_impulse + o) * n +
                          load<F>(p.tangent_impulse[0] + o) * t0 +
                          load<F>(p.tangent_impulse[1] + o) * t1;
    v.apply(load3<F>(p.ra, o), load3<F>(p.rb, o), impulse);
  }
  v.write(b, o, bodies);
}

template <int W>
ZONESIM_WIDE_INLINE void frictionLanes(BlockLanes& b, int o, SolverBodies& bodies) {
  using F = typename Simd<W>::F;
  Pair<W> v(b, o, bodies);
  // Friction: both tangents from the same velocities, then the pair clamped to the Coulomb
  // disc (as Jolt does), one application per point.
  const V3<F> t0 = load3<F>(b.tangent[0], o), t1 = load3<F>(b.tangent[1], o);
  const F friction = load<F>(b.friction + o);
  for (int i = 0; i < b.points; ++i) {
    PointLanes& p = b.point[i];
    const V3<F> ra = load3<F>(p.ra, o), rb = load3<F>(p.rb, o);
    const F limit = friction * load<F>(p.normal_impulse + o);
    const V3<F> dv = (v.vb + cross(v.wb, rb)) - (v.va + cross(v.wa, ra));
    const F old0 = load<F>(p.tangent_impulse[0] + o), old1 = load<F>(p.tangent_impulse[1] + o);
    F j0 = old0 - load<F>(p.tangent_mass[0] + o) * dot(dv, t0);
    F j1 = old1 - load<F>(p.tangent_mass[1] + o) * dot(dv, t1);
    // Clamped to the disc: scaled by limit / |j| where |j| is over it (lanes under it, or at
    // |j| = 0, keep a scale of 1; their quotient is discarded).
    const F size2 = j0 * j0 + j1 * j1;
    const F scale = size2 > limit * limit ? limit / vsqrt<W>(size2) : splat<F>(1.0f);
    j0 = j0 * scale;
    j1 = j1 * scale;
    store(p.tangent_impulse[0] + o, j0);
    store(p.tangent_impulse[1] + o, j1);
    v.apply(ra, rb, (j0 - old0) * t0 + (j1 - old1) * t1);
  }
  v.write(b, o, bodies);
}

template <int W>
ZONESIM_WIDE_INLINE void normalLanes(BlockLanes& b, BounceLanes* bounce, int o,
                                     SolverBodies& bodies, const SoftPass& pass) {
  using F = typename Simd<W>::F;
  Pair<W> v(b, o, bodies);
  V3<F> pa, qa, pb, qb;
  gather<W>(bodies.displacement.data(), b.read_a + o, pa, qa);
  gather<W>(bodies.displacement.data(), b.read_b + o, pb, qb);
  const V3<F> n = load3<F>(b.normal, o);
  const auto fixed = load<F>(b.fixed + o) > splat<F>(0.0f);
  const F zero = splat<F>(0.0f), one = splat<F>(1.0f);
  const F rate = fixed ? splat<F>(pass.soft_fixed.bias_rate) : splat<F>(pass.soft.bias_rate);
  const F mass_scale =
      fixed ? splat<F>(pass.soft_fixed.mass_scale) : splat<F>(pass.soft.mass_scale);
  const F impulse_scale =
      fixed ? splat<F>(pass.soft_fixed.impulse_scale) : splat<F>(pass.soft.impulse_scale);
  const F inv_h = splat<F>(pass.inv_h), push_limit = splat<F>(-pass.max_push);
  // Separation moves with the relative displacement of the anchors (small-angle rotation).
  const F moved = dot(n, pb - pa);
  for (int i = 0; i < b.points; ++i) {
    PointLanes& p = b.point[i];
    const NormalRow<F> row(load3<F>(p.ra, o), load3<F>(p.rb, o), n, v.ia, v.ib);
    const F s = load<F>(p.separation + o) + moved + dot(row.cb, qb) - dot(row.ca, qa);
    // Speculative (s > 0): may close the gap within this sub-step. Else the soft spring with
    // the bias, or the rigid relax pass without.
    const auto gap = s > zero;
    F bias = gap ? s * inv_h : zero;
    F ms = one, is = zero;
    if (pass.use_bias) {
      bias = gap ? bias : vmax(rate * s, push_limit);
      ms = gap ? one : mass_scale;
      is = gap ? zero : impulse_scale;
    }
    const F vn = v.normalVelocity(n, row.ca, row.cb);
    const F old = load<F>(p.normal_impulse + o);
    const F delta = -(load<F>(p.normal_mass + o) * ms) * (vn + bias) - is * old;
    const F impulse = vmax(zero, old + delta);
    store(p.normal_impulse + o, impulse);
    if (bounce) {
      float* most = bounce->max_normal_impulse[i] + o;
      store(most, vmax(load<F>(most), impulse));
    }
    v.applyNormal(n, row.ia_ca, row.ib_cb, impulse - old);
  }
  v.write(b, o, bodies);
}

template <int W>
ZONESIM_WIDE_INLINE void restituteLanes(BlockLanes& b, const BounceLanes& bounce, int o,
                                        SolverBodies& bodies, float threshold) {
  using F = typename Simd<W>::F;
  Pair<W> v(b, o, bodies);
  const V3<F> n = load3<F>(b.normal, o);
  const F e = load<F>(b.restitution + o), zero = splat<F>(0.0f);
  const auto bouncy = e != zero;
  for (int i = 0; i < b.points; ++i) {
    PointLanes& p = b.point[i];
    const F approach = load<F>(bounce.approach[i] + o);
    // Only points that were approaching fast and actually pushed this step bounce.
    const auto bounces = bouncy & (approach <= splat<F>(-threshold)) &
                         (load<F>(bounce.max_normal_impulse[i] + o) != zero);
    const NormalRow<F> row(load3<F>(p.ra, o), load3<F>(p.rb, o), n, v.ia, v.ib);
    const F vn = v.normalVelocity(n, row.ca, row.cb);
    const F old = load<F>(p.normal_impulse + o);
    const F bounced = vmax(zero, old - load<F>(p.normal_mass + o) * (vn + e * approach));
    const F impulse = bounces ? bounced : old;
    store(p.normal_impulse + o, impulse);
    v.applyNormal(n, row.ia_ca, row.ib_cb, impulse - old);
  }
  v.write(b, o, bodies);
}

template <int W>
ZONESIM_WIDE_INLINE void buildRowsAll(BlockLanes& b) {
  for (int o = 0; o < kBlockLanes; o += W) buildRowsLanes<W>(b, o);
}

template <int W>
ZONESIM_WIDE_INLINE void warmStartAll(std::span<const BlockLanes> blocks, SolverBodies& bodies) {
  for (const BlockLanes& b : blocks)
    for (int o = 0; o < kBlockLanes; o += W) warmStartLanes<W>(b, o, bodies);
}

template <int W>
ZONESIM_WIDE_INLINE void solveAll(std::span<BlockLanes> blocks, std::span<BounceLanes> bounces,
                                  SolverBodies& bodies, const SoftPass& pass) {
  // Friction for every contact first, then the normals (as the scalar soft step does, and
  // why: physics/contact_solver_soft.cpp).
  if (pass.friction) {
    for (BlockLanes& b : blocks)
      for (int o = 0; o < kBlockLanes; o += W) frictionLanes<W>(b, o, bodies);
  }
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    BounceLanes* bounce = bounces.empty() ? nullptr : &bounces[k];
    for (int o = 0; o < kBlockLanes; o += W) normalLanes<W>(blocks[k], bounce, o, bodies, pass);
  }
}

template <int W>
ZONESIM_WIDE_INLINE void restituteAll(std::span<BlockLanes> blocks,
                                      std::span<const BounceLanes> bounces, SolverBodies& bodies,
                                      float threshold) {
  for (std::size_t k = 0; k < blocks.size(); ++k)
    for (int o = 0; o < kBlockLanes; o += W)
      restituteLanes<W>(blocks[k], bounces[k], o, bodies, threshold);
}

// One function per width; the 8-lane ones alone are compiled for AVX2 (the rest of the library
// stays baseline x86-64, so it runs where AVX2 is missing).
#if defined(ZONESIM_WIDE_AVX2)

ZONESIM_WIDE_TARGET_AVX2 void buildRows8(BlockLanes& b) {
  buildRowsAll<8>(b);
}
ZONESIM_WIDE_TARGET_AVX2 void warmStart8(std::span<const BlockLanes> blocks, SolverBodies& bodies) {
  warmStartAll<8>(blocks, bodies);
}
ZONESIM_WIDE_TARGET_AVX2 void solve8(std::span<BlockLanes> blocks, std::span<BounceLanes> bounces,
                                     SolverBodies& bodies, const SoftPass& pass) {
  solveAll<8>(blocks, bounces, bodies, pass);
}
ZONESIM_WIDE_TARGET_AVX2 void restitute8(std::span<BlockLanes> blocks,
                                         std::span<const BounceLanes> bounces, SolverBodies& bodies,
                                         float threshold) {
  restituteAll<8>(blocks, bounces, bodies, threshold);
}
#endif

}  // namespace

int supportedLanes(int wanted) {
#if defined(ZONESIM_WIDE_AVX2)
  static const bool kAvx2 = __builtin_cpu_supports("avx2");
  if (wanted >= 8 && kAvx2) return 8;
#endif
  return wanted >= 4 ? 4 : 1;
}

void buildRows(int lanes, BlockLanes& block) {
#if defined(ZONESIM_WIDE_AVX2)
  if (lanes == 8) return buildRows8(block);
#endif
  if (lanes == 4) return buildRowsAll<4>(block);
  buildRowsAll<1>(block);
}

void warmStart(int lanes, std::span<const BlockLanes> blocks, SolverBodies& bodies) {
#if defined(ZONESIM_WIDE_AVX2)
  if (lanes == 8) return warmStart8(blocks, bodies);
#endif
  if (lanes == 4) return warmStartAll<4>(blocks, bodies);
  warmStartAll<1>(blocks, bodies);
}

void solve(int lanes, std::span<BlockLanes> blocks, std::span<BounceLanes> bounces,
           SolverBodies& bodies, const SoftPass& pass) {
#if defined(ZONESIM_WIDE_AVX2)
  if (lanes == 8) return solve8(blocks, bounces, bodies, pass);
#endif
  if (lanes == 4) return solveAll<4>(blocks, bounces, bodies, pass);
  solveAll<1>(blocks, bounces, bodies, pass);
}

void restitute(int lanes, std::span<BlockLanes> blocks, std::span<const BounceLanes> bounces,
               SolverBodies& bodies, float threshold) {
#if defined(ZONESIM_WIDE_AVX2)
  if (lanes == 8) return restitute8(blocks, bounces, bodies, threshold);
#endif
  if (lanes == 4) return restituteAll<4>(blocks, bounces, bodies, threshold);
  restituteAll<1>(blocks, bounces, bodies, threshold);
}

}  // namespace zonesim::physics::wide
