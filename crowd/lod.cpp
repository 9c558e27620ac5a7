#include "crowd/lod.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

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

void crowdingCounts(std::span<const Vec2> agents, std::span<const std::uint8_t> counted,
                    std::span<const Vec2> others, double cell, std::vector<std::uint32_t>& out) {
  if (!(cell > 0.0)) throw std::invalid_argument("crowdingCounts: cell must be > 0");
  if (!counted.empty() && counted.size() != agents.size())
    throw std::invalid_argument("crowdingCounts: counted and agents differ in size");
  out.assign(agents.size(), 0);
  if (agents.empty()) return;
  const auto cellOf = [cell](Vec2 p) {
    return std::pair{std::int64_t(std::floor(p.x / cell)), std::int64_t(std::floor(p.y / cell))};
  };
  // A dense array over the occupied cells' bounds when that is small, else a hash map.
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  std::int64_t x0 = kMax, x1 = -kMax, y0 = kMax, y1 = -kMax;
  for (std::span<const Vec2> set : {agents, others}) {
    for (Vec2 p : set) {
      const auto [cx, cy] = cellOf(p);
      x0 = std::min(x0, cx), x1 = std::max(x1, cx), y0 = std::min(y0, cy), y1 = std::max(y1, cy);
    }
  }
  const std::size_t points = agents.size() + others.size();
  const double area = double(x1 - x0 + 1) * double(y1 - y0 + 1);
  const bool dense = area <= 4.0 * double(points) + 4096.0;
  std::vector<std::uint32_t> grid(dense ? std::size_t(area) : 0, 0);
  std::unordered_map<std::int64_t, std::uint32_t> sparse;
  const std::int64_t width = x1 - x0 + 1;
  const auto slot = [&](Vec2 p) -> std::uint32_t& {
    const auto [cx, cy] = cellOf(p);
    const std::int64_t key = (cy - y0) * width + (cx - x0);
    return dense ? grid[std::size_t(key)] : sparse[key];
  };
  for (std::size_t i = 0; i < agents.size(); ++i)
    if (counted.empty() || counted[i]) ++slot(agents[i]);
  for (Vec2 p : others) ++slot(p);
  for (std::size_t i = 0; i < agents.size(); ++i) out[i] = slot(agents[i]);
}

LevelOfDetail::LevelOfDetail(const LodSettings& settings) : settings_(settings) {
  if (settings.mid_every < 1 || settings.far_every < 1 || settings.near_radius < 0 ||
      settings.far_radius < settings.near_radius)
    throw std::invalid_argument("LodSettings: periods >= 1 and 0 <= nearRadius <= farRadius");
  if (settings.crowded_count < 0 || !(settings.crowded_cell > 0.0))
    throw std::invalid_argument("LodSettings: crowded_count >= 0 and crowded_cell > 0");
}

StepPlan LevelOfDetail::plan(std::span<const std::uint64_t> ids, std::span<const Vec2> pos,
                             std::span<const Vec2> players, std::int64_t tick, double dt,
                             std::span<std::int64_t> last_tick,
                             std::span<const std::uint32_t> crowding) {
  const std::size_t n = ids.size();
  if (pos.size() != n || (!last_tick.empty() && last_tick.size() != n) ||
      (!crowding.empty() && crowding.size() != n))
    throw std::invalid_argument("LevelOfDetail::plan: array sizes differ");
  const bool crowd_check = settings_.crowded_count > 0 && !crowding.empty();
  dt_.assign(n, 0.0);
  steer_.assign(n, 0);
  level_.assign(n, 0);
  counts_[0] = counts_[1] = counts_[2] = 0;
  updated_ = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const LodLevel level = crowd_check && crowding[i] >= std::uint32_t(settings_.crowded_count)
                               ? LodLevel::Near
                               : lodLevel(pos[i], players, settings_);
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
