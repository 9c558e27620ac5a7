#include "ai/adapt/guards.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace zonesim::ai::adapt {

namespace {

using Field = double NpcParams::*;
using RangeField = ParamRange NpcRanges::*;
constexpr std::array<std::pair<Field, RangeField>, 3> kFields{{
    {&NpcParams::accuracy, &NpcRanges::accuracy},
    {&NpcParams::aggression, &NpcRanges::aggression},
    {&NpcParams::reaction_steps, &NpcRanges::reaction_steps},
}};

bool sane(double v, const ParamRange& r) {
  const double width = r.hi - r.lo;
  return std::isfinite(v) && v >= r.lo - width && v <= r.hi + width;
}

}  // namespace

AdaptGuard::AdaptGuard(const GuardLimits& limits) : limits_(limits) {
  if (!(limits.max_step > 0 && limits.max_step <= 1))
    throw std::invalid_argument("adaptation max_step must be in (0, 1]");
  for (auto [field, range] : kFields) {
    const ParamRange& r = limits.ranges.*range;
    if (!(r.lo <= r.hi) || !r.holds(limits.defaults.*field))
      throw std::invalid_argument("adaptation defaults must lie within their ranges");
  }
}

NpcParams AdaptGuard::step(const NpcParams& current, const NpcParams& proposed) {
  ++stats_.steps;
  NpcParams target = proposed;
  bool broken = false;
  for (auto [field, range] : kFields) broken |= !sane(proposed.*field, limits_.ranges.*range);
  if (broken) {
    ++stats_.fallbacks;
    target = limits_.defaults;
  }
  bool clamped = false, limited = false;
  NpcParams next = current;
  for (auto [field, range] : kFields) {
    const ParamRange& r = limits_.ranges.*range;
    const double want = std::clamp(target.*field, r.lo, r.hi);
    clamped |= want != target.*field;
    // A current value outside its range (a corrupted state) is first brought back into it.
    const double from = std::isfinite(current.*field) ? std::clamp(current.*field, r.lo, r.hi)
                                                      : (limits_.defaults.*field);
    const double room = limits_.max_step * (r.hi - r.lo);
    next.*field = std::clamp(want, from - room, from + room);
    limited |= next.*field != want;
  }
  stats_.clamped += clamped ? 1 : 0;
  stats_.rate_limited += limited ? 1 : 0;
  return next;
}

}  // namespace zonesim::ai::adapt
