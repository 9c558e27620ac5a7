#pragma once
// Which body pairs began and ended touching in a step: the pairs with a contact (within the
// contact margin, awake or asleep) after the step, against those before it.

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "physics/contact_solver.h"

namespace zonesim::physics {

/// A pair of bodies, lower index first.
using BodyPair = std::pair<BodyIndex, BodyIndex>;

/// Keeps the last step's touching pairs and reports the changes.
class ContactEvents {
 public:
  /// The touching pairs are now those of `awake` and `asleep` (each sorted by pair): records
  /// which began and which ended since the last update.
  void update(std::span<const BodyContact> awake, std::span<const BodyContact> asleep);
  /// Pairs that touch now and did not at the last update, in pair order.
  std::span<const BodyPair> begun() const { return begun_; }
  /// Pairs that touched at the last update and do not now, in pair order.
  std::span<const BodyPair> ended() const { return ended_; }

 private:
  std::vector<BodyPair> touching_, before_, begun_, ended_;
};

}  // namespace zonesim::physics
