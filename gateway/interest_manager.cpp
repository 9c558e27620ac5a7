#include "gateway/interest_manager.h"

#include <algorithm>
#include <iterator>

namespace zonesim::gateway {

InterestManager::InterestManager(const InterestGrid& grid, double radius, double hysteresis)
    : grid_(grid), radius_(radius), hysteresis_(hysteresis) {}

void InterestManager::acquire(int cell, CellDelta& delta) {
  if (++refcount_[cell] == 1) delta.added.push_back(cell);
}

void InterestManager::release(int cell, CellDelta& delta) {
  auto it = refcount_.find(cell);
  if (it == refcount_.end()) return;
  if (--it->second == 0) {
    refcount_.erase(it);
    delta.removed.push_back(cell);
  }
}

void InterestManager::update(std::uint64_t player, double x, double z, CellDelta& delta,
                             double radius) {
  std::vector<int>& held = held_[player];
  double r = radius > 0 ? radius : radius_;
  std::vector<int> wanted = grid_.cellsWithin(x, z, r);
  std::vector<int> keep_zone = grid_.cellsWithin(x, z, r + hysteresis_);
  // next = wanted ∪ (held ∩ keep_zone); all lists ascending.
  std::vector<int> kept, next;
  std::set_intersection(held.begin(), held.end(), keep_zone.begin(), keep_zone.end(),
                        std::back_inserter(kept));
  std::set_union(wanted.begin(), wanted.end(), kept.begin(), kept.end(), std::back_inserter(next));
  std::vector<int> gained, lost;
  std::set_difference(next.begin(), next.end(), held.begin(), held.end(),
                      std::back_inserter(gained));
  std::set_difference(held.begin(), held.end(), next.begin(), next.end(), std::back_inserter(lost));
  for (int c : gained) acquire(c, delta);
  for (int c : lost) release(c, delta);
  held = std::move(next);
}

void InterestManager::remove(std::uint64_t player, CellDelta& delta) {
  auto it = held_.find(player);
  if (it == held_.end()) return;
  for (int c : it->second) release(c, delta);
  held_.erase(it);
}

const std::vector<int>& InterestManager::cellsOf(std::uint64_t player) const {
  static const std::vector<int> kNone;
  auto it = held_.find(player);
  return it == held_.end() ? kNone : it->second;
}

int InterestManager::refcount(int cell) const {
  auto it = refcount_.find(cell);
  return it == refcount_.end() ? 0 : it->second;
}

void InterestManager::cellsHeld(std::vector<std::pair<int, int>>& out) const {
  out.assign(refcount_.begin(), refcount_.end());
  std::sort(out.begin(), out.end());
}

}  // namespace zonesim::gateway
