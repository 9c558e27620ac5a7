#include "physics/contact_events.h"

#include <algorithm>
#include <iterator>

namespace zonesim::physics {

void ContactEvents::update(std::span<const BodyContact> awake,
                           std::span<const BodyContact> asleep) {
  before_.swap(touching_);
  touching_.clear();
  // Merge the two sorted lists into distinct pairs (a compound pair has one contact per piece).
  std::size_t i = 0, j = 0;
  while (i < awake.size() || j < asleep.size()) {
    const bool from_awake = j == asleep.size() || (i < awake.size() && awake[i] < asleep[j]);
    const BodyContact& c = from_awake ? awake[i++] : asleep[j++];
    const BodyPair pair{c.a, c.b};
    if (touching_.empty() || touching_.back() != pair) touching_.push_back(pair);
  }
  begun_.clear();
  ended_.clear();
  std::set_difference(touching_.begin(), touching_.end(), before_.begin(), before_.end(),
                      std::back_inserter(begun_));
  std::set_difference(before_.begin(), before_.end(), touching_.begin(), touching_.end(),
                      std::back_inserter(ended_));
}

}  // namespace zonesim::physics
