#pragma once
// The scene's `time_dilation` key: how the cluster slows its clock under overload (EVE's TiDi).

namespace zonesim {

/// Time dilation (zone_node/time_dilation.h): when the slowest zone's tick work does not fit
/// its wall-clock period, the cluster stretches that period (dt stays fixed) in steps of
/// `step` down to `min_factor`, and speeds up again when the work falls.
struct TimeDilationSettings {
  bool enabled = false;      ///< off unless the scene (or --time-dilation) turns it on
  double min_factor = 0.1;   ///< the slowest the clock may run (sim seconds per wall second)
  double step = 0.1;         ///< the factor moves in multiples of this (1, 0.9, ..., min_factor)
  int window = 10;           ///< ticks of work averaged before each decision
  double slow_above = 0.9;   ///< slow down when work exceeds this fraction of the period
  double speed_below = 0.6;  ///< speed up when work at the faster step stays under this
  int recover_windows = 3;   ///< windows in a row under speed_below before each step up
};

}  // namespace zonesim
