#include "crowd/lod.h"

#include <algorithm>
#include <stdexcept>

#include "common/splitmix.h"

namespace zonesim::crowd {

LodLevel lodLevel(Vec2 pos, std::span<const Vec2> players, const LodSettings& settings) {
  double d2 = 1e300;
  for (Vec2 p : players) d2 = std::min(d2, lengthSq(pos - p));
  if (d2 <= settings.near_radius * settings.near_radius) return LodLevel::Near;
  return d2 <= settings.far_radius * settings.far_radius ? LodLevel::Mid : LodLevel::Far;
}

int lodPeriod(LodLevel level, const LodSettings& settings) {
  return level == LodLevel::Near  ? 1
         : level == LodLevel::Mid ? settings.mid_every
                                  : settings.far_every;
}

bool lodDue(std::uint64_t id, std::int64_t tick, int every) {
  return (std::uint64_t(tick) + splitmix64(id)) % std::uint64_t(every) == 0;
}

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
  for (std::size_t i = 0; i < n; ++i) {
    const LodLevel level = lodLevel(pos[i], players, settings_);
    const int lvl = int(level);
    level_[i] = std::uint8_t(lvl);
    ++counts_[lvl];
    const int every = lodPeriod(level, settings_);
    const bool due = lodDue(ids[i], tick, every);
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
