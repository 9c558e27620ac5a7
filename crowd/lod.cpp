#include "crowd/lod.h"

#include <stdexcept>

#include "common/splitmix.h"

namespace zonesim::crowd {

LevelOfDetail::LevelOfDetail(const LodSettings& settings) : settings_(settings) {
  if (settings.mid_every < 1 || settings.far_every < 1 || settings.near_radius < 0 ||
      settings.far_radius < settings.near_radius)
    throw std::invalid_argument("LodSettings: periods >= 1 and 0 <= nearRadius <= farRadius");
}

StepPlan LevelOfDetail::plan(std::span<const std::uint64_t> ids, std::span<const Vec2> pos,
                             std::span<const Vec2> players, std::int64_t tick, double dt,
                             std::span<std::int64_t> last_tick) {
  const std::size_t n = ids.size();
  if (pos.size() != n || (!last_tick.empty() && last_tick.size() != n))
    throw std::invalid_argument("LevelOfDetail::plan: array sizes differ");
  dt_.assign(n, 0.0);
  steer_.assign(n, 0);
  level_.assign(n, 0);
  counts_[0] = counts_[1] = counts_[2] = 0;
  updated_ = 0;
  const double near2 = settings_.near_radius * settings_.near_radius;
  const double far2 = settings_.far_radius * settings_.far_radius;
  for (std::size_t i = 0; i < n; ++i) {
    double d2 = 1e300;
    for (Vec2 p : players) d2 = std::min(d2, lengthSq(pos[i] - p));
    int lvl = d2 <= near2 ? 0 : (d2 <= far2 ? 1 : 2);
    level_[i] = std::uint8_t(lvl);
    ++counts_[lvl];
    const int every = lvl == 0 ? 1 : (lvl == 1 ? settings_.mid_every : settings_.far_every);
    const bool due = (std::uint64_t(tick) + splitmix64(ids[i])) % std::uint64_t(every) == 0;
    const bool fresh = !last_tick.empty() && last_tick[i] < 0;
    if (!due && !fresh) continue;
    if (last_tick.empty()) {
      dt_[i] = every * dt;
    } else {
      dt_[i] = fresh ? dt : double(tick - last_tick[i]) * dt;
      last_tick[i] = tick;
    }
    steer_[i] = lvl == 0 || (lvl == 1 ? settings_.mid_steers : settings_.far_steers);
    ++updated_;
  }
  return StepPlan{dt_, steer_};
}

}  // namespace zonesim::crowd
