#include "common/scene_loader_time_dilation.h"

#include <string>

namespace zonesim {

void readTimeDilation(const SceneMap& root, TimeDilationSettings& td) {
  if (!root.optional("time_dilation")) return;
  td.enabled = true;  // a section that is there means on, unless it says enabled: false
  SceneMap m = root.section("time_dilation", {"enabled", "min_factor", "step", "window",
                                              "slow_above", "speed_below", "recover_windows"});
  m.read("enabled", td.enabled);
  m.read("min_factor", td.min_factor, Limit{0, 1, true});
  m.read("step", td.step, Limit{0, 1, true});
  m.read("window", td.window, Limit::between(1, 10000));
  m.read("slow_above", td.slow_above, Limit{0, 1, true});
  m.read("speed_below", td.speed_below, Limit{0, 1, true});
  m.read("recover_windows", td.recover_windows, Limit::between(1, 10000));
  // Speeding up must leave the work under the slow-down line, or the clock would oscillate.
  if (td.speed_below >= td.slow_above) {
    m.failAt("speed_below", formatNumber(td.speed_below) + " must be below slow_above (" +
                                formatNumber(td.slow_above) + ")");
  }
}

}  // namespace zonesim
