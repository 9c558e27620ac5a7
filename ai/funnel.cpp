#include "ai/funnel.h"

#include <cstddef>

namespace zonesim::ai {

namespace {

// Twice the signed area of (a, b, c): > 0 when c lies left of the ray a -> b.
double cross(Vec2 a, Vec2 b, Vec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// One gate of a funnel from `apex` with sides through `left` and `right`: each side narrows to
// the gate's end when that lies inside the funnel. A side that would cross the other ends the
// funnel there: the other side's point is the next corner of the path (`corner` -1: the left
// point, +1: the right one; the right side is tried first).
struct Gate {
  bool right = false, left = false;  // the side narrowed to this gate
  int corner = 0;
};

Gate admit(Vec2 apex, Vec2& left, Vec2& right, Vec2 l, Vec2 r) {
  Gate g;
  if (cross(apex, right, r) >= 0) {
    if (apex == right || cross(apex, left, r) < 0) {
      right = r;
      g.right = true;
    } else {
      g.corner = -1;
      return g;
    }
  }
  if (cross(apex, left, l) <= 0) {
    if (apex == left || cross(apex, right, l) > 0) {
      left = l;
      g.left = true;
    } else {
      g.corner = 1;
    }
  }
  return g;
}

}  // namespace

std::vector<Vec2> pullString(Vec2 start, const std::vector<FunnelPortal>& portals, Vec2 goal) {
  StringPuller puller(start);
  for (const FunnelPortal& p : portals) puller.add(p);
  puller.add({goal, goal});  // the goal as a degenerate portal at the corridor's end
  std::vector<Vec2> path = puller.corners();
  if (!(goal == path.back())) path.push_back(goal);
  return path;
}

StringPuller::StringPuller(Vec2 start)
    : gates_{{start, start}}, corners_{start}, apex_(start), left_(start), right_(start) {}

void StringPuller::add(const FunnelPortal& portal) {
  gates_.push_back(portal);
  for (; next_ < gates_.size(); ++next_) {
    const Gate g = admit(apex_, left_, right_, gates_[next_].left, gates_[next_].right);
    right_at_ = g.right ? next_ : right_at_;
    left_at_ = g.left ? next_ : left_at_;
    if (g.corner == 0) continue;
    // The corner becomes the apex; the scan restarts after the gate it came from.
    const Vec2 corner = g.corner < 0 ? left_ : right_;
    const std::size_t at = g.corner < 0 ? left_at_ : right_at_;
    if (!(corner == corners_.back())) corners_.push_back(corner);
    apex_ = left_ = right_ = corner;
    left_at_ = right_at_ = at;
    next_ = at;
  }
}

}  // namespace zonesim::ai
