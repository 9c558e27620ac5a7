#include "ai/jump_point_search.h"

#include <algorithm>
#include <cstdlib>

#include "ai/fixed_cost.h"
#include "ai/open_order.h"
#include "ai/search_generation.h"

namespace zonesim::ai {

namespace {

int sign(int v) {
  return (v > 0) - (v < 0);
}

constexpr int kDx[8] = {1, -1, 0, 0, 1, -1, 1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, 1, -1, -1};

/// Index of (dx, dy) in kDx / kDy, by table: the JPS+ search reads it for every jump.
int directionIndex(int dx, int dy) {
  static constexpr int kIndex[9] = {7, 3, 6, 1, -1, 0, 5, 2, 4};  // by (dy + 1) * 3 + dx + 1
  return kIndex[(dy + 1) * 3 + dx + 1];
}

/// Steps from `from` along the direction to reach `to`, when `to` lies exactly on that ray
/// (straight: same row or column; diagonal: on the diagonal), else -1.
int stepsOnRay(int x, int y, int dx, int dy, int tx, int ty) {
  const int ex = tx - x, ey = ty - y;
  if (dx == 0 ? ex != 0 : (sign(ex) != dx)) return -1;
  if (dy == 0 ? ey != 0 : (sign(ey) != dy)) return -1;
  if (dx != 0 && dy != 0 && std::abs(ex) != std::abs(ey)) return -1;
  return dx != 0 ? std::abs(ex) : std::abs(ey);
}

}  // namespace

JumpPointSearch::JumpPointSearch(const GridMap& map, Jumps jumps)
    : map_(map),
      jumps_(jumps),
      nodes_(std::size_t(map.width()) * std::size_t(map.height()), Node{0, -1, 0}) {}

void JumpPointSearch::syncCells() {
  if (synced_version_ == map_.version() && !open_.empty()) return;
  padded_width_ = map_.width() + 2;
  open_.assign(std::size_t(padded_width_) * std::size_t(map_.height() + 2), 0);
  for (int y = 0; y < map_.height(); ++y) {
    for (int x = 0; x < map_.width(); ++x) {
      open_[std::size_t(y + 1) * std::size_t(padded_width_) + std::size_t(x + 1)] =
          map_.passableAt(map_.index(x, y)) ? 1 : 0;
    }
  }
  synced_version_ = map_.version();
  if (jumps_ == Jumps::Precomputed) precompute();
}

void JumpPointSearch::precompute() {
  const int w = map_.width(), h = map_.height();
  for (auto& table : distance_) table.assign(open_.size(), 0);
  // Does entering (x, y) moving straight along (dx, dy) make it a jump point (a forced
  // neighbour, as in jumpStraight)?
  auto forced = [&](int x, int y, int dx, int dy) {
    if (dx != 0) {
      return (walkable(x, y - 1) && !walkable(x - dx, y - 1)) ||
             (walkable(x, y + 1) && !walkable(x - dx, y + 1));
    }
    return (walkable(x - 1, y) && !walkable(x - 1, y - dy)) ||
           (walkable(x + 1, y) && !walkable(x + 1, y - dy));
  };
  // One step further than the next cell's value: towards its jump point or its wall.
  auto further = [](std::int32_t next) { return next > 0 ? next + 1 : next - 1; };
  // Straight directions, each scanned so that the next cell along it is done first.
  for (int d = 0; d < 4; ++d) {
    const int dx = kDx[d], dy = kDy[d];
    std::vector<std::int32_t>& t = distance_[d];
    for (int i = 0; i < w * h; ++i) {
      // Walk rows (or columns) against the direction.
      const int y = dy > 0 ? h - 1 - i / w : (dy < 0 ? i / w : i / w);
      const int x = dx > 0 ? w - 1 - i % w : (dx < 0 ? i % w : i % w);
      if (!walkable(x, y)) continue;
      const int nx = x + dx, ny = y + dy;
      if (!walkable(nx, ny)) {
        t[padded(x, y)] = 0;
      } else {
        t[padded(x, y)] = forced(nx, ny, dx, dy) ? 1 : further(t[padded(nx, ny)]);
      }
    }
  }
  // Diagonals: the next cell is one row further along dy, so rows go against dy.
  for (int d = 4; d < 8; ++d) {
    const int dx = kDx[d], dy = kDy[d];
    const int along_x = directionIndex(dx, 0), along_y = directionIndex(0, dy);
    std::vector<std::int32_t>& t = distance_[d];
    for (int r = 0; r < h; ++r) {
      const int y = dy > 0 ? h - 1 - r : r;
      for (int x = 0; x < w; ++x) {
        if (!walkable(x, y)) continue;
        const int nx = x + dx, ny = y + dy;
        if (!walkable(x + dx, y) || !walkable(x, y + dy) || !walkable(nx, ny)) {
          t[padded(x, y)] = 0;
        } else if (distance_[along_x][padded(nx, ny)] > 0 ||
                   distance_[along_y][padded(nx, ny)] > 0) {
          t[padded(x, y)] = 1;
        } else {
          t[padded(x, y)] = further(t[padded(nx, ny)]);
        }
      }
    }
  }
}

int JumpPointSearch::jump(int x, int y, int dx, int dy) const {
  const bool diagonal = dx != 0 && dy != 0;
  if (jumps_ == Jumps::Scanned) {
    return diagonal ? jumpDiagonal(x, y, dx, dy) : jumpStraight(x, y, dx, dy);
  }
  const std::int32_t t = distance_[directionIndex(dx, dy)][padded(x, y)];
  const int reach = t > 0 ? t : -t;
  if (!diagonal) {
    // The goal is a jump point of every search: stop there if it lies within reach.
    const int to_goal = stepsOnRay(x, y, dx, dy, goal_x_, goal_y_);
    if (to_goal > 0 && to_goal <= reach) return map_.index(goal_x_, goal_y_);
  } else if (sign(goal_x_ - x) == dx && sign(goal_y_ - y) == dy) {
    // Goal in this quadrant: stop where the diagonal meets its row or column, if in reach.
    const int steps = std::min(std::abs(goal_x_ - x), std::abs(goal_y_ - y));
    if (steps <= reach) return map_.index(x + steps * dx, y + steps * dy);
  }
  return t > 0 ? map_.index(x + t * dx, y + t * dy) : -1;
}

void JumpPointSearch::beginSearch() {
  nextGeneration(generation_, nodes_);
  heap_.clear();
  stats_ = SearchStats{};
}

int JumpPointSearch::jumpStraight(int x, int y, int dx, int dy) const {
  for (;;) {
    x += dx;
    y += dy;
    if (!walkable(x, y)) return -1;
    if (x == goal_x_ && y == goal_y_) return map_.index(x, y);
    // A side cell whose cell behind is blocked is reachable optimally only through here.
    if (dx != 0) {
      if ((walkable(x, y - 1) && !walkable(x - dx, y - 1)) ||
          (walkable(x, y + 1) && !walkable(x - dx, y + 1))) {
        return map_.index(x, y);
      }
    } else if ((walkable(x - 1, y) && !walkable(x - 1, y - dy)) ||
               (walkable(x + 1, y) && !walkable(x + 1, y - dy))) {
      return map_.index(x, y);
    }
  }
}

int JumpPointSearch::jumpDiagonal(int x, int y, int dx, int dy) const {
  for (;;) {
    // No corner cutting: both cardinal cells beside the diagonal step must be open.
    if (!walkable(x + dx, y) || !walkable(x, y + dy) || !walkable(x + dx, y + dy)) return -1;
    x += dx;
    y += dy;
    if (x == goal_x_ && y == goal_y_) return map_.index(x, y);
    if (jumpStraight(x, y, dx, 0) >= 0 || jumpStraight(x, y, 0, dy) >= 0) {
      return map_.index(x, y);
    }
  }
}

bool JumpPointSearch::findPath(Cell start, Cell goal, GridPath& out) {
  out.clear();
  beginSearch();
  if (!map_.passable(start.x, start.y) || !map_.passable(goal.x, goal.y)) return false;
  syncCells();
  goal_x_ = goal.x;
  goal_y_ = goal.y;
  const std::uint32_t open = generation_, closed = generation_ + 1;
  const int w = map_.width();
  const int start_idx = map_.index(start.x, start.y), goal_idx = map_.index(goal.x, goal.y);
  nodes_[start_idx] = Node{0, -1, open};
  heap_.push_back(HeapEntry{octileFixed(start.x - goal.x, start.y - goal.y), 0, start_idx});
  ++stats_.generated;
  struct Direction {
    int dx, dy;
  };
  Direction dirs[8];
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), PopsLater{});
    const HeapEntry top = heap_.back();
    heap_.pop_back();
    Node& cur = nodes_[top.idx];
    if (cur.stamp == closed || top.g != cur.g) continue;  // a stale entry (lazy decrease-key)
    cur.stamp = closed;
    ++stats_.expanded;
    if (top.idx == goal_idx) {
      tracePath(goal_idx, out);
      return true;
    }
    const int x = top.idx % w, y = top.idx / w;
    // The directions worth a jump: all eight from the start; otherwise the one it came in on,
    // a diagonal's two components, and the forced neighbours of a straight move.
    int count = 0;
    if (cur.parent < 0) {
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (dx != 0 || dy != 0) dirs[count++] = {dx, dy};
    } else {
      const int dx = sign(x - cur.parent % w), dy = sign(y - cur.parent / w);
      dirs[count++] = {dx, dy};
      if (dx != 0 && dy != 0) {
        dirs[count++] = {dx, 0};
        dirs[count++] = {0, dy};
      } else if (dx != 0) {
        for (int side : {-1, 1}) {
          if (walkable(x, y + side) && !walkable(x - dx, y + side)) {
            dirs[count++] = {0, side};
            dirs[count++] = {dx, side};
          }
        }
      } else {
        for (int side : {-1, 1}) {
          if (walkable(x + side, y) && !walkable(x + side, y - dy)) {
            dirs[count++] = {side, 0};
            dirs[count++] = {side, dy};
          }
        }
      }
    }
    for (int k = 0; k < count; ++k) {
      const auto [dx, dy] = dirs[k];
      const int jp = jump(x, y, dx, dy);
      if (jp < 0) continue;
      Node& n = nodes_[jp];
      if (n.stamp == closed) continue;
      const int jx = jp % w, jy = jp / w;
      const std::int64_t g = cur.g + octileFixed(jx - x, jy - y);
      if (n.stamp == open && n.g <= g) continue;
      n = Node{g, top.idx, open};
      heap_.push_back(HeapEntry{g + octileFixed(jx - goal.x, jy - goal.y), g, jp});
      std::push_heap(heap_.begin(), heap_.end(), PopsLater{});
      ++stats_.generated;
    }
  }
  return false;
}

void JumpPointSearch::tracePath(int goal, GridPath& out) const {
  // Jump points from the goal back, each segment straight or diagonal: fill in its cells.
  const int w = map_.width();
  out.cells.clear();
  out.cells.push_back(map_.cellAt(goal));
  for (int i = goal; nodes_[i].parent >= 0; i = nodes_[i].parent) {
    const int p = nodes_[i].parent;
    const int dx = sign(p % w - i % w), dy = sign(p / w - i / w);
    Cell c = map_.cellAt(i);
    const Cell to = map_.cellAt(p);
    while (!(c == to)) {
      c.x += dx;
      c.y += dy;
      out.cells.push_back(c);
    }
  }
  std::reverse(out.cells.begin(), out.cells.end());
  out.length = pathLength(out.cells);
}

}  // namespace zonesim::ai
