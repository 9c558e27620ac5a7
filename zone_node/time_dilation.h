#pragma once
// Time dilation (EVE Online's TiDi): when the slowest zone cannot do a tick's work within its
// wall-clock period, the cluster stretches the period instead of running late. dt never
// changes, so a dilated run reaches bit for bit the states of an undilated one, only later.
//
// The factor (sim seconds per wall second) moves on a ladder 1, 1 - step, ..., min_factor.
// Every `window` ticks the controller compares the window's mean work of the slowest rank
// with the dilated period dt / factor:
//   - above slow_above of it: down to the first step whose period fits the work (at once,
//     several steps if needed: an overload should not run late for several windows);
//   - under speed_below of the next faster step's period for recover_windows windows in a
//     row: up one step. After a step up the work is under speed_below < slow_above of the
//     new period, so the clock cannot bounce straight back down (hysteresis).
// No MPI here: every rank feeds the same allreduced work, so every rank steps alike.

#include <cstdint>

#include "common/scene_time_dilation.h"

namespace zonesim::zone {

/// The cluster's clock rate, decided from the slowest rank's tick work.
class TimeDilation {
 public:
  /// `tick_rate` is the scene's ticks per wall second at full speed (the undilated period is
  /// 1 / tick_rate).
  TimeDilation(const TimeDilationSettings& settings, double tick_rate);

  /// Feeds the slowest rank's work (wall seconds) of the tick just run, `next_tick` being the
  /// tick to run next; returns true when the factor changed (from `next_tick` on).
  bool record(double slowest_work_seconds, std::uint64_t next_tick);

  /// Sim seconds per wall second: 1 at full speed, min_factor at the slowest.
  double factor() const { return factorAt(level_); }
  /// The first tick run at factor().
  std::uint64_t sinceTick() const { return since_tick_; }
  /// Wall seconds per tick at the current factor.
  double periodSeconds() const { return base_period_ / factor(); }
  /// Steps taken (down and up) so far.
  std::uint64_t changes() const { return changes_; }
  /// The factor of ladder step `level` (0: full speed).
  double factorAt(int level) const;
  /// The slowest step.
  int lowestLevel() const { return lowest_level_; }

 private:
  TimeDilationSettings s_;
  double base_period_;
  int lowest_level_;  // index of min_factor on the ladder
  int level_ = 0;
  int ticks_in_window_ = 0;
  double window_work_ = 0;
  int quiet_windows_ = 0;  // windows in a row that would fit the next faster step
  std::uint64_t since_tick_ = 0;
  std::uint64_t changes_ = 0;
};

}  // namespace zonesim::zone
