#include "physics/islands.h"

#include <algorithm>

namespace zonesim::physics {

namespace {
constexpr std::uint32_t kNoIsland = SleepState::kNoGroup;
}  // namespace

void Islands::resize(std::size_t n) {
  asleep_.resize(n, 0);
  rest_time_.resize(n, 0.0);
  island_.resize(n, kNoIsland);
  island_rest_.resize(n);
}

std::size_t Islands::sleepingCount() const {
  return static_cast<std::size_t>(std::count(asleep_.begin(), asleep_.end(), 1));
}

void Islands::setState(std::size_t i, const SleepState& s) {
  asleep_[i] = s.asleep ? 1 : 0;
  rest_time_[i] = s.rest_time;
  island_[i] = s.asleep ? s.group : kNoIsland;
}

void Islands::wake(std::size_t i) {
  if (!asleep_[i]) return;
  const std::uint32_t id = island_[i];
  // Rare (a touch or a user call): a scan of the arrays is cheaper than keeping member lists.
  for (std::size_t k = 0; k < asleep_.size(); ++k) {
    if (asleep_[k] && island_[k] == id) {
      asleep_[k] = 0;
      rest_time_[k] = 0.0;
      island_[k] = kNoIsland;
    }
  }
}

void Islands::update(BodyStorage& bodies, std::span<const BodyContact> contacts,
                     const SleepSettings& settings, double dt) {
  const std::size_t n = bodies.size();
  resize(n);
  sets_.reset(n);
  for (const BodyContact& c : contacts) {
    // Statics and kinematics do not join islands: a floor would merge everything on it.
    if (bodies.inv_mass[c.a] == 0.0 || bodies.inv_mass[c.b] == 0.0) continue;
    sets_.unite(c.a, c.b);  // the smaller index becomes the root: deterministic island ids
  }
  const double v2 = settings.linear_speed * settings.linear_speed;
  const double w2 = settings.angular_speed * settings.angular_speed;
  std::fill(island_rest_.begin(), island_rest_.end(), 1e300);
  for (std::size_t i = 0; i < n; ++i) {
    if (asleep_[i] || bodies.inv_mass[i] == 0.0) continue;
    const bool resting = bodies.linear_velocity[i].squaredNorm() < v2 &&
                         bodies.angular_velocity[i].squaredNorm() < w2;
    rest_time_[i] = resting ? rest_time_[i] + dt : 0.0;
    const std::uint32_t root = sets_.find(static_cast<std::uint32_t>(i));
    island_rest_[root] = std::min(island_rest_[root], rest_time_[i]);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (asleep_[i] || bodies.inv_mass[i] == 0.0) continue;
    const std::uint32_t root = sets_.find(static_cast<std::uint32_t>(i));
    if (island_rest_[root] < settings.time_to_sleep) continue;
    asleep_[i] = 1;
    island_[i] = root;
    bodies.linear_velocity[i].setZero();
    bodies.angular_velocity[i].setZero();
  }
}

}  // namespace zonesim::physics
