#pragma once
// State guards between whatever proposes an NPC (the model, the rubber band) and the game:
// - a proposal that is not finite, or lies beyond its range by more than the range's own width
//   (the proposer is broken, not just eager), is replaced by the defaults;
// - otherwise each parameter is clamped to its range;
// - and moves at most max_step of its range's width per adaptation step, the fallback too, so
//   no proposal, however wild, makes an NPC jump.

#include <cstdint>

#include "ai/adapt/npc_params.h"

namespace zonesim::ai::adapt {

/// What the guards hold the NPC to.
struct GuardLimits {
  NpcRanges ranges;
  double max_step = 0.1;  ///< fraction of a parameter's range it may move per adaptation step
  NpcParams defaults = paramsForDifficulty(kDefaultDifficulty);
};

/// What the guards did, over a run.
struct GuardStats {
  std::uint64_t steps = 0;
  std::uint64_t fallbacks = 0;     ///< proposals replaced by the defaults
  std::uint64_t clamped = 0;       ///< proposals with a parameter outside its range
  std::uint64_t rate_limited = 0;  ///< steps that moved a parameter less than proposed
};

/// Applies the guards, one adaptation step at a time.
class AdaptGuard {
 public:
  /// `limits.max_step` must be in (0, 1] and the defaults within the ranges (checked).
  explicit AdaptGuard(const GuardLimits& limits = {});

  /// The NPC after one step from `current` towards `proposed`.
  NpcParams step(const NpcParams& current, const NpcParams& proposed);
  /// The limits held.
  const GuardLimits& limits() const { return limits_; }
  /// What the guards did so far.
  const GuardStats& stats() const { return stats_; }

 private:
  GuardLimits limits_;
  GuardStats stats_;
};

}  // namespace zonesim::ai::adapt
