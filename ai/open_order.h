#pragma once
// The order in which the A* searches (grid, HPA abstract graph, waypoint graph) take entries
// off their open lists, written once so that every search breaks ties the same way.

namespace zonesim::ai {

/// Strict "a comes off the open list before b" for entries with f, g and idx: lower f, then
/// deeper g (fewer re-expansions of equal-f plateaus), then lower index so that ties never
/// depend on insertion order.
template <typename E>
bool popsBefore(const E& a, const E& b) {
  if (a.f != b.f) return a.f < b.f;
  if (a.g != b.g) return a.g > b.g;
  return a.idx < b.idx;
}

/// popsBefore as the comparator of std::push_heap / std::pop_heap (a max-heap: the entry that
/// pops first must compare greatest).
struct PopsLater {
  template <typename E>
  bool operator()(const E& a, const E& b) const {
    return popsBefore(b, a);
  }
};

}  // namespace zonesim::ai
