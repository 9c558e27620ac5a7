#include "physics/step_lod.h"

#include <algorithm>
#include <climits>

namespace zonesim::physics {

namespace {
constexpr int kMaxPeriod = 64;
// A held body's debt stops growing here: a world that never reaches a due step (a period
// changed every step) must not overflow.
constexpr int kMaxLag = 1 << 20;
}  // namespace

void StepLod::resize(std::size_t n) {
  period_.resize(n, 1);
  lag_.resize(n, 0);
  pass_of_.resize(n, kNoPass);
}

void StepLod::setPeriod(BodyIndex i, int period) {
  period = std::clamp(period, 1, kMaxPeriod);
  longer_periods_ += (period > 1) - (period_[i] > 1);
  period_[i] = period;
}

void StepLod::setLag(BodyIndex i, int lag) {
  lag = std::clamp(lag, 0, kMaxLag);
  lagging_ += std::size_t(lag > 0) - std::size_t(lag_[i] > 0);
  lag_[i] = lag;
}

void StepLod::plan(const BodyStorage& bodies, std::span<const BodyContact> contacts,
                   const DistanceJoints& joints, const RigidJoints& rigid_joints,
                   std::span<const std::uint8_t> asleep, std::uint64_t step,
                   int longest_period) {
  const std::size_t n = bodies.size();
  resize(n);
  sets_.reset(n);
  // Immovable bodies link nothing: a floor would make every pile on it one island.
  const auto movable = [&](BodyIndex i) { return i != kNoBody && bodies.inv_mass[i] != 0.0; };
  for (const BodyContact& c : contacts)
    if (movable(c.a) && movable(c.b)) sets_.unite(c.a, c.b);
  const auto joined = [&](BodyIndex a, BodyIndex b) {
    if (movable(a) && movable(b)) sets_.unite(a, b);
  };
  for (const DistanceJoint& j : joints.joints()) joined(j.a, j.b);
  rigid_joints.forEachPair(joined);

  island_period_.assign(n, INT_MAX);
  island_lag_.assign(n, INT_MAX);
  const auto steps = [&](std::size_t i) {
    return bodies.type[i] != BodyType::Static && !asleep[i];
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!steps(i)) continue;
    // A kinematic body follows its script: it never waits.
    const int period =
        bodies.type[i] == BodyType::Kinematic ? 1 : std::min(period_[i], longest_period);
    const std::uint32_t root = sets_.find(static_cast<std::uint32_t>(i));
    island_period_[root] = std::min(island_period_[root], period);
    island_lag_[root] = std::min(island_lag_[root], lag_[i]);
  }
  // Every due island's step length, then the passes in ascending length.
  pass_ticks_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    pass_of_[i] = kNoPass;
    if (!steps(i)) continue;
    const std::uint32_t root = sets_.find(static_cast<std::uint32_t>(i));
    const int period = island_period_[root];
    if (period > 1 && step % static_cast<std::uint64_t>(period) != 0) continue;
    // The island's body that owes least sets the length: none steps past the present.
    pass_of_[i] = island_lag_[root] + 1;
    if (std::find(pass_ticks_.begin(), pass_ticks_.end(), pass_of_[i]) == pass_ticks_.end())
      pass_ticks_.push_back(pass_of_[i]);
  }
  std::sort(pass_ticks_.begin(), pass_ticks_.end());
  for (int& pass : pass_of_) {
    if (pass == kNoPass) continue;
    pass = static_cast<int>(std::lower_bound(pass_ticks_.begin(), pass_ticks_.end(), pass) -
                            pass_ticks_.begin());
  }
}

void StepLod::finish(const BodyStorage& bodies, std::span<const std::uint8_t> stepped,
                     std::span<const std::uint8_t> asleep) {
  lagging_ = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (bodies.type[i] == BodyType::Static) {
      lag_[i] = 0;
      continue;
    }
    if (stepped[i]) {
      lag_[i] = 0;
      ++bodies_stepped_;
    } else if (asleep[i]) {
      lag_[i] = 0;  // At rest: the time it skipped changes nothing.
    } else {
      lag_[i] = std::min(lag_[i] + 1, kMaxLag);
      ++bodies_held_;
    }
    lagging_ += lag_[i] > 0;
  }
}

}  // namespace zonesim::physics
