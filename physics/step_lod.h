#pragma once
// Level of detail in time for a physics world. Each body has a step period (1: every step; k:
// it may step every k-th step, for bodies far from everyone who could see them). An island,
// the bodies linked by contacts or joints, takes the shortest period among its bodies, so a
// pile touched by one near body steps every step as a whole. An island with period k steps on
// the world's steps that are multiples of k, by the time it skipped: (lag + 1) dt, where lag
// counts the steps its bodies were held still. Islands that take the same step length are
// solved together in one pass, shortest first. With every period 1 the plan is one pass of
// every body: the plain step.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/body_storage.h"
#include "physics/contact_solver.h"
#include "physics/distance_joints.h"
#include "physics/rigid_joints.h"
#include "physics/union_find.h"

namespace zonesim::physics {

/// Per-body step periods and lags, and the passes of one world step.
class StepLod {
 public:
  /// Marks a body that steps in no pass of this step.
  static constexpr int kNoPass = -1;

  /// Grows the per-body arrays to n bodies (new bodies: period 1, no lag).
  void resize(std::size_t n);
  /// Body i may step every `period` steps (1-64; clamped).
  void setPeriod(BodyIndex i, int period);
  /// Sets the steps body i still owes (0 up to a bound; a rebuilt world's restored lags).
  void setLag(BodyIndex i, int lag);
  /// The period set for body i.
  int period(BodyIndex i) const { return period_[i]; }
  /// Steps body i was held still and still owes (0 after it steps).
  int lag(BodyIndex i) const { return lag_[i]; }
  /// True while every body has period 1 and no lag: the world takes its plain step.
  bool idle() const { return longer_periods_ == 0 && lagging_ == 0; }

  /// Plans world step number `step`: islands from last step's contacts and the joints, each
  /// island's period and lag, and the pass each awake movable body steps in (kNoPass: held).
  /// `asleep` marks sleeping bodies, which step in no pass and owe nothing. No island's period
  /// exceeds `longest_period`.
  void plan(const BodyStorage& bodies, std::span<const BodyContact> contacts,
            const DistanceJoints& joints, const RigidJoints& rigid_joints,
            std::span<const std::uint8_t> asleep, std::uint64_t step, int longest_period);
  /// Steps of dt each pass of the plan takes, in pass order (ascending).
  std::span<const int> passTicks() const { return pass_ticks_; }
  /// The pass body i steps in, or kNoPass.
  int passOf(BodyIndex i) const { return pass_of_[i]; }
  /// After the passes: bodies that stepped owe nothing; awake bodies that were held owe one
  /// step more. `stepped`: per body, whether it moved in some pass (woken bodies did too).
  void finish(const BodyStorage& bodies, std::span<const std::uint8_t> stepped,
              std::span<const std::uint8_t> asleep);
  /// Body steps taken and held since the start (each body counts once per world step).
  std::uint64_t bodiesStepped() const { return bodies_stepped_; }
  std::uint64_t bodiesHeld() const { return bodies_held_; }

 private:
  std::vector<int> period_, lag_, pass_of_;
  UnionFind sets_;
  std::vector<int> island_period_, island_lag_;
  std::vector<int> pass_ticks_;
  std::uint64_t bodies_stepped_ = 0, bodies_held_ = 0;
  std::size_t longer_periods_ = 0;  // bodies with period > 1
  std::size_t lagging_ = 0;         // bodies with lag > 0
};

}  // namespace zonesim::physics
