#pragma once
// String pulling through a corridor of portals: the "simple stupid funnel" (after Mikko
// Mononen's description). The funnel keeps an apex and two boundary points; each portal narrows
// a side when its end lies inside the funnel, and a side that would cross the other makes the
// other side's point a corner of the path and the new apex. The result is the shortest path
// from start to goal inside the corridor, as its corner points. Portals are used as given: the
// mesh's erosion already keeps the agent radius, so nothing is shrunk here.

#include <cstddef>
#include <vector>

#include "ai/vec2.h"

namespace zonesim::ai {

/// A portal as the traveller meets it: `left` and `right` relative to the direction of travel
/// (left: cross(direction, left - right) > 0 with cross(u, v) = u.x*v.y - u.y*v.x).
struct FunnelPortal {
  Vec2 left;   ///< end on the left of the travel direction
  Vec2 right;  ///< end on the right
};

/// Corner points of the shortest path from `start` through `portals` (in order) to `goal`:
/// start first, goal last, no two consecutive points equal.
std::vector<Vec2> pullString(Vec2 start, const std::vector<FunnelPortal>& portals, Vec2 goal);

/// pullString one portal at a time: the corners are final as soon as they are found (later
/// portals cannot move them), so a caller that needs only where to head next stops reading the
/// corridor at the first corner (crowd/flow_waypoints.h).
class StringPuller {
 public:
  explicit StringPuller(Vec2 start);
  /// The next portal of the corridor; the goal goes last as a degenerate one, {goal, goal}.
  void add(const FunnelPortal& portal);
  /// The start and every corner found so far (the goal once added and bent at, or not at all:
  /// pullString appends it).
  const std::vector<Vec2>& corners() const { return corners_; }

 private:
  std::vector<FunnelPortal> gates_;  // the start as a degenerate gate, then every portal
  std::vector<Vec2> corners_;
  Vec2 apex_, left_, right_;
  std::size_t left_at_ = 0, right_at_ = 0;  // the gates the sides last narrowed to
  std::size_t next_ = 1;                    // the next gate to admit
};

}  // namespace zonesim::ai
