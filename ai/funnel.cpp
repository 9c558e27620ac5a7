#include "ai/funnel.h"

#include <cstddef>

namespace zonesim::ai {

namespace {

// Twice the signed area of (a, b, c): > 0 when c lies left of the ray a -> b.
double cross(Vec2 a, Vec2 b, Vec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

}  // namespace

std::vector<Vec2> pullString(Vec2 start, const std::vector<FunnelPortal>& portals, Vec2 goal) {
  // The corridor with the start and the goal as degenerate portals at its ends.
  std::vector<FunnelPortal> gates;
  gates.reserve(portals.size() + 2);
  gates.push_back({start, start});
  gates.insert(gates.end(), portals.begin(), portals.end());
  gates.push_back({goal, goal});

  std::vector<Vec2> path{start};
  Vec2 apex = start, left = start, right = start;
  std::size_t left_at = 0, right_at = 0;
  auto newApex = [&](Vec2 corner, std::size_t at) {
    if (!(corner == path.back())) path.push_back(corner);
    apex = left = right = corner;
    left_at = right_at = at;
  };
  for (std::size_t i = 1; i < gates.size(); ++i) {
    const Vec2 l = gates[i].left, r = gates[i].right;
    // Right side: narrows when r is not right of the current right boundary.
    if (cross(apex, right, r) >= 0) {
      if (apex == right || cross(apex, left, r) < 0) {
        right = r;
        right_at = i;
      } else {
        // r crosses the left boundary: the left point is a corner; restart after it.
        std::size_t at = left_at;
        newApex(left, at);
        i = at;
        continue;
      }
    }
    // Left side, mirrored.
    if (cross(apex, left, l) <= 0) {
      if (apex == left || cross(apex, right, l) > 0) {
        left = l;
        left_at = i;
      } else {
        std::size_t at = right_at;
        newApex(right, at);
        i = at;
        continue;
      }
    }
  }
  if (!(goal == path.back())) path.push_back(goal);
  return path;
}

}  // namespace zonesim::ai
