#include "crowd/lod.h"

#include <stdexcept>

#include "common/splitmix.h"

namespace zonesim::crowd {

LevelOfDetail::LevelOfDetail(const LodSettings& settings) : settings_(settings) {
  if (settings.midEvery < 1 || settings.farEvery < 1 || settings.nearRadius < 0 ||
      settings.farRadius < settings.nearRadius)
    throw std::invalid_argument("LodSettings: periods >= 1 and 0 <= nearRadius <= farRadius");
}

StepPlan LevelOfDetail::plan(std::span<const std::uint64_t> ids, std::span<const Vec2> pos,
                             std::span<const Vec2> players, std::int64_t tick, double dt,
                             std::span<std::int64_t> lastTick) {
  const std::size_t n = ids.size();
  if (pos.size() != n || (!lastTick.empty() && lastTick.size() != n))
    throw std::invalid_argument("LevelOfDetail::plan: array sizes differ");
  dt_.assign(n, 0.0);
  steer_.assign(n, 0);
  level_.assign(n, 0);
  counts_[0] = counts_[1] = counts_[2] = 0;
  updated_ = 0;
  const double near2 = settings_.nearRadius * settings_.nearRadius;
  const double far2 = settings_.farRadius * settings_.farRadius;
  for (std::size_t i = 0; i < n; ++i) {
    double d2 = 1e300;
    for (Vec2 p : players) d2 = std::min(d2, lengthSq(pos[i] - p));
    int lvl = d2 <= near2 ? 0 : (d2 <= far2 ? 1 : 2);
    level_[i] = std::uint8_t(lvl);
    ++counts_[lvl];
    const int every = lvl == 0 ? 1 : (lvl == 1 ? settings_.midEvery : settings_.farEvery);
    const bool due = (std::uint64_t(tick) + splitmix64(ids[i])) % std::uint64_t(every) == 0;
    const bool fresh = !lastTick.empty() && lastTick[i] < 0;
    if (!due && !fresh) continue;
    if (lastTick.empty()) {
      dt_[i] = every * dt;
    } else {
      dt_[i] = fresh ? dt : double(tick - lastTick[i]) * dt;
      lastTick[i] = tick;
    }
    steer_[i] = lvl == 0 || (lvl == 1 ? settings_.midSteers : settings_.farSteers);
    ++updated_;
  }
  return StepPlan{dt_, steer_};
}

}  // namespace zonesim::crowd
