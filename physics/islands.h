#pragma once
// Islands and sleeping: bodies linked by contacts form islands (union-find); an island whose
// bodies have all been slow for long enough falls asleep as a whole and costs nothing until a
// moving body touches it or it is woken.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/body_storage.h"
#include "physics/contact_solver.h"
#include "physics/union_find.h"

namespace zonesim::physics {

/// Thresholds for putting islands to sleep.
struct SleepSettings {
  bool enabled = false;
  double linear_speed = 0.05;   ///< m/s: slower counts as resting.
  double angular_speed = 0.05;  ///< rad/s.
  double time_to_sleep = 0.5;   ///< s an island must rest before sleeping.
};

/// One body's sleep: asleep or not, how long it has rested, and, when asleep, the island it
/// fell asleep with (named by that island's root body index; waking one wakes them all).
struct SleepState {
  static constexpr std::uint32_t kNoGroup = 0xffffffffu;
  bool asleep = false;
  double rest_time = 0.0;
  std::uint32_t group = kNoGroup;
};

/// Tracks rest time per body and the sleeping islands.
class Islands {
 public:
  /// Grows the per-body arrays to n bodies (new bodies are awake).
  void resize(std::size_t n);
  /// True when body i is asleep.
  bool asleep(std::size_t i) const { return asleep_[i] != 0; }
  /// Body i's sleep, to carry it into another world holding the same body.
  SleepState state(std::size_t i) const { return {asleep_[i] != 0, rest_time_[i], island_[i]}; }
  /// Sets body i's sleep (group: the index of its island's root body in this world, or any
  /// value that names the island: bodies with equal groups wake together).
  void setState(std::size_t i, const SleepState& s);
  /// Wakes body i and every body that fell asleep in its island.
  void wake(std::size_t i);
  /// After a solved step: accumulates rest time and puts resting islands to sleep, zeroing their
  /// velocities. Contacts link only bodies that move (non-zero inverse mass).
  void update(BodyStorage& bodies, std::span<const BodyContact> contacts,
              const SleepSettings& settings, double dt);
  /// Number of bodies asleep.
  std::size_t sleepingCount() const;
  /// Per body, 1 when asleep.
  std::span<const std::uint8_t> asleepMask() const { return asleep_; }

 private:
  std::vector<std::uint8_t> asleep_;
  std::vector<double> rest_time_;
  UnionFind sets_;                     // this step's contacts
  std::vector<std::uint32_t> island_;  // Root id an asleep body slept with.
  std::vector<double> island_rest_;
};

}  // namespace zonesim::physics
