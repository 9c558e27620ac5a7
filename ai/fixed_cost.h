#pragma once
// Grid costs in fixed point for the searches (A*, jump point search): a cardinal step is 2^40,
// a diagonal sqrt(2) * 2^40 rounded. Doubles summed from 1 and sqrt(2) in different orders
// differ in their last bits and break f ties arbitrarily; integer sums tie exactly and compare
// fast, and the octile heuristic in the same units stays consistent.

#include <cstdint>

namespace zonesim::ai {

inline constexpr std::int64_t kStraight = std::int64_t(1) << 40;
inline constexpr std::int64_t kDiagonal = 1554944255988;  // sqrt(2) * 2^40, rounded

/// Octile distance in fixed-point units.
inline std::int64_t octileFixed(int dx, int dy) {
  dx = dx < 0 ? -dx : dx;
  dy = dy < 0 ? -dy : dy;
  const int lo = dx < dy ? dx : dy, hi = dx < dy ? dy : dx;
  return std::int64_t(hi - lo) * kStraight + std::int64_t(lo) * kDiagonal;
}

}  // namespace zonesim::ai
