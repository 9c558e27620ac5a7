#include "zone_node/time_dilation.h"

#include <cmath>

namespace zonesim::zone {

TimeDilation::TimeDilation(const TimeDilationSettings& settings, double tick_rate)
    : s_(settings), base_period_(1.0 / tick_rate) {
  // The last step is min_factor itself, also when it is not a multiple of step below 1. The
  // small tolerance keeps 1 - 9 * 0.1 (0.0999...) from adding a step below 0.1.
  lowest_level_ = int(std::ceil((1.0 - s_.min_factor) / s_.step - 1e-9));
  if (lowest_level_ < 0) lowest_level_ = 0;
}

double TimeDilation::factorAt(int level) const {
  if (level >= lowest_level_) return s_.min_factor;
  // Rounded to a millionth, so that the announced steps read 0.7, not 0.7000000000000001.
  return std::round((1.0 - double(level) * s_.step) * 1e6) / 1e6;
}

bool TimeDilation::record(double slowest_work_seconds, std::uint64_t next_tick) {
  window_work_ += slowest_work_seconds;
  if (++ticks_in_window_ < s_.window) return false;
  const double work = window_work_ / double(ticks_in_window_);
  window_work_ = 0;
  ticks_in_window_ = 0;
  auto period = [&](int level) { return base_period_ / factorAt(level); };
  int next = level_;
  if (work > s_.slow_above * period(level_)) {
    while (next < lowest_level_ && work > s_.slow_above * period(next)) ++next;
    quiet_windows_ = 0;
  } else if (level_ > 0 && work < s_.speed_below * period(level_ - 1)) {
    if (++quiet_windows_ >= s_.recover_windows) {
      next = level_ - 1;
      quiet_windows_ = 0;
    }
  } else {
    quiet_windows_ = 0;
  }
  if (next == level_) return false;
  level_ = next;
  since_tick_ = next_tick;
  ++changes_;
  return true;
}

}  // namespace zonesim::zone
