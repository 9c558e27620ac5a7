#include "crowd/keep_apart.h"

#include <algorithm>
#include <cmath>

namespace zonesim::crowd {

namespace {

constexpr double kTolerance = 1e-12;  // m: rounding allowed on a limit

// How hard the limits are: every overlap backed off by half its depth; by as much as the
// reach allows; or only not deepened (each overlap's line moves toward the origin).
enum class Ask { kHalfDepth, kReach, kNoDeeper };

double offsetOf(const GapPlane& p, Ask ask, double reach) {
  switch (ask) {
    case Ask::kHalfDepth:
      return p.offset;
    case Ask::kReach:
      return std::max(p.offset, -reach);
    case Ask::kNoDeeper:
      break;
  }
  return std::max(p.offset, 0.0);
}

// The point of plane j's line closest to `wish` that keeps planes [0, j) and the reach; false
// when that part of the line is empty.
bool bestOnLine(std::span<const GapPlane> planes, std::size_t j, Ask ask, Vec2 wish, double reach,
                Vec2& out) {
  const Vec2 n = planes[j].normal;
  const double c = offsetOf(planes[j], ask, reach);
  const double inside = reach * reach - c * c;
  if (inside < 0.0) return false;  // the line misses the disc
  const Vec2 base = n * c;
  const Vec2 along{-n.y, n.x};
  double lo = -std::sqrt(inside), hi = std::sqrt(inside);
  for (std::size_t i = 0; i < j; ++i) {
    const double slope = dot(along, planes[i].normal);
    const double room = offsetOf(planes[i], ask, reach) - dot(base, planes[i].normal);
    if (std::abs(slope) <= kTolerance) {
      if (room < -kTolerance) return false;  // parallel, and the whole line is outside
      continue;
    }
    if (slope > 0.0)
      hi = std::min(hi, room / slope);
    else
      lo = std::max(lo, room / slope);
  }
  if (lo > hi + kTolerance) return false;
  const double t = lo > hi ? 0.5 * (lo + hi) : std::clamp(dot(wish - base, along), lo, hi);
  out = base + along * t;
  return true;
}

}  // namespace

void KeepApart::neighbour(Vec2 rel, bool self_first) {
  const double d2 = lengthSq(rel);
  GapPlane p;
  double d;
  if (d2 > 1e-18) {
    d = std::sqrt(d2);
    p.normal = rel * (1.0 / d);
  } else {
    d = 0.0;  // one point: the lower id backs off toward -x, as separation pushes it
    p.normal = {self_first ? 1.0 : -1.0, 0.0};
  }
  p.offset = 0.5 * (d - 2.0 * radius_);
  if (p.offset >= reach_) return;  // farther than any move this step: cannot bind
  planes_.push_back(p);
}

namespace {

// The displacement closest to `wish` within the reach and the planes asked as `ask`; false
// when there is none.
bool closest(std::span<const GapPlane> planes, Ask ask, Vec2 wish, double reach, Vec2& out) {
  // Incremental: the optimum for the planes so far either keeps the next one, or lies on its
  // line (the objective, distance to the wish, is convex).
  Vec2 x = clampLength(wish, reach);
  for (std::size_t j = 0; j < planes.size(); ++j) {
    if (dot(x, planes[j].normal) <= offsetOf(planes[j], ask, reach)) continue;
    if (!bestOnLine(planes, j, ask, wish, reach, x)) return false;
  }
  out = x;
  return true;
}

}  // namespace

Vec2 KeepApart::solve(Vec2 wish) const {
  Vec2 x;
  if (closest(planes_, Ask::kHalfDepth, wish, reach_, x)) return x;
  // An overlap deeper than twice the reach: back off as fast as the reach allows.
  if (closest(planes_, Ask::kReach, wish, reach_, x)) return x;
  // Squeezed: some overlap cannot be backed off from. Staying put keeps every plane asked not
  // to deepen, so this succeeds; the fallback to zero only guards against rounding.
  if (closest(planes_, Ask::kNoDeeper, wish, reach_, x) && keeps(x)) return x;
  return {};
}

Vec2 KeepApart::move(Vec2 wish) const {
  const Vec2 x = solve(wish);
  // Free: no gap held it back (a wish a few ulp past the reach is only clamped, not sidestepped).
  if (x == wish || x == clampLength(wish, reach_)) return x;
  // With a sidestep only as far as ahead, and only when less than half the move was left,
  // 132 of the courtyard's 400 flow NPCs never got through its doors (docs/benchmarks.md).
  constexpr double kSidestep = 3.0;
  // Not compared with x: x is the nearest move to the wish that keeps every gap, so keeping
  // the nearer of the two would never sidestep (242 instead of 357 of the courtyard's 400
  // through in 130 s; docs/benchmarks.md).
  return solve(wish + Vec2{wish.y, -wish.x} * kSidestep);
}

void gatherGaps(const NeighbourGrid& grid, std::int32_t self, KeepApart& k) {
  const double q = k.queryRadius(), q2 = q * q;
  const std::span<const GridEntry> entries = grid.entries();
  const double* xs = grid.xs();
  const double* ys = grid.ys();
  const Vec2 p = entries[self].pos;
  const std::uint64_t id = entries[self].id;
  grid.forEachRowNear(p, q, [&](std::int32_t begin, std::int32_t end) {
    for (std::int32_t j = begin; j < end; ++j) {
      const Vec2 rel{xs[j] - p.x, ys[j] - p.y};
      if (j != self && lengthSq(rel) < q2) k.neighbour(rel, id < entries[j].id);
    }
  });
}

bool KeepApart::keeps(Vec2 x) const {
  if (lengthSq(x) > reach_ * reach_ * (1.0 + 1e-12) + kTolerance) return false;
  for (const GapPlane& p : planes_)
    if (dot(x, p.normal) > offsetOf(p, Ask::kNoDeeper, reach_) + kTolerance) return false;
  return true;
}

}  // namespace zonesim::crowd
