#include "ai/jump_point_search.h"

#include <algorithm>
#include <cstdlib>

#include "ai/fixed_cost.h"

namespace zonesim::ai {

namespace {

int sign(int v) {
  return (v > 0) - (v < 0);
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

/// Bits needed for coordinates below `width`.
int bitsFor(int width) {
  int shift = 0;
  while ((1 << shift) < width) ++shift;
  return shift;
}

}  // namespace

JumpPointSearch::JumpPointSearch(const GridMap& map, Jumps jumps,
                                 const LandmarkHeuristic* landmarks)
    : map_(map),
      jumps_(jumps),
      landmarks_(landmarks),
      shift_(bitsFor(map.width())),
      nodes_(std::size_t(map.height()) << shift_, Node{0, -1}),
      stamps_(nodes_.size(), 0) {}

void JumpPointSearch::beginSearch() {
  if (generation_ > 0xFFFF - 2 * kStamps) {
    std::fill(stamps_.begin(), stamps_.end(), 0);
    generation_ = 0;
  }
  generation_ += kStamps;
  open_.clear();
  stats_ = SearchStats{};
}

void JumpPointSearch::syncCells() {
  if (synced_version_ == map_.version()) return;
  rows_ = BitGrid(map_, false);
  columns_ = BitGrid(map_, true);
  synced_version_ = map_.version();
  if (jumps_ == Jumps::Precomputed) tables_.build(rows_);
}

[[gnu::always_inline]] inline bool JumpPointSearch::isBend(int x, int y, int dx, int dy,
                                                           int& turn_x, int& turn_y) const {
  // Coming in along x, the way on is along y (and the other way round); straight ahead must be
  // blocked, exactly one side open, and the corner between the way in and the way on blocked.
  if (dx != 0) {
    if (walkable(x + dx, y) || walkable(x, y - 1) == walkable(x, y + 1)) return false;
    turn_x = 0;
    turn_y = walkable(x, y + 1) ? 1 : -1;
    return !walkable(x - dx, y + turn_y);
  }
  if (walkable(x, y + dy) || walkable(x - 1, y) == walkable(x + 1, y)) return false;
  turn_x = walkable(x + 1, y) ? 1 : -1;
  turn_y = 0;
  return !walkable(x + turn_x, y - dy);
}

[[gnu::always_inline]] inline JumpPointSearch::Jump JumpPointSearch::jumpStraight(int x, int y,
                                                                                  int dx,
                                                                                  int dy) const {
  if (jumps_ == Jumps::Precomputed) {
    const std::int32_t t = tables_.distance(JpsPlusTables::direction(dx, dy), x, y);
    // The goal is a jump point of every search: stop there if it lies within reach.
    const int to_goal = stepsOnRay(x, y, dx, dy, goal_x_, goal_y_);
    if (to_goal > 0 && to_goal <= (t > 0 ? t : -t)) return Jump{goal_idx_, 0, 0};
    if (t <= 0) return Jump{-1, 0, 0};
    Jump j{node(x + t * dx, y + t * dy), 0, 0};
    if (!isBend(x + t * dx, y + t * dy, dx, dy, j.turn_x, j.turn_y)) j.turn_x = j.turn_y = 0;
    return j;
  }
  // Along the line's positions: a row (x varies) or a column (y varies).
  const bool horizontal = dy == 0;
  const int line = horizontal ? y : x, pos = horizontal ? x : y, dir = horizontal ? dx : dy;
  const BitGrid& bits = horizontal ? rows_ : columns_;
  const BitGrid::Stop stop = dir > 0 ? bits.scanUp(line, pos) : bits.scanDown(line, pos);
  // The goal is reached when it lies on the line between here and the last cell scanned.
  if ((horizontal ? goal_y_ : goal_x_) == line) {
    const int goal_pos = horizontal ? goal_x_ : goal_y_;
    const int last = stop.jump ? stop.at : stop.at - dir;
    if ((goal_pos - pos) * dir > 0 && (last - goal_pos) * dir >= 0) return Jump{goal_idx_, 0, 0};
  }
  if (!stop.jump) return Jump{-1, 0, 0};
  // A bend turns onto the side line: across the rows for a row, across the columns for one.
  return horizontal ? Jump{node(stop.at, y), 0, stop.turn} : Jump{node(x, stop.at), stop.turn, 0};
}

[[gnu::always_inline]] inline bool JumpPointSearch::stepDiagonal(int& x, int& y, int dx,
                                                                 int dy) const {
  if (jumps_ == Jumps::Scanned) {
    // No corner cutting: both cardinal cells beside the diagonal step must be open.
    if (!walkable(x + dx, y) || !walkable(x, y + dy) || !walkable(x + dx, y + dy)) return false;
    x += dx;
    y += dy;
    return true;
  }
  const std::int32_t t = tables_.distance(JpsPlusTables::direction(dx, dy), x, y);
  const int reach = t > 0 ? t : -t;
  if (sign(goal_x_ - x) == dx && sign(goal_y_ - y) == dy) {
    // Goal in this quadrant: stop where the diagonal meets its row or column, if in reach
    // (straight jumps from there find the goal).
    const int steps = std::min(std::abs(goal_x_ - x), std::abs(goal_y_ - y));
    if (steps <= reach) {
      x += steps * dx;
      y += steps * dy;
      return true;
    }
  }
  if (t <= 0) return false;
  x += t * dx;
  y += t * dy;
  return true;
}

void JumpPointSearch::relaxJump(int from, int x, int y, std::int64_t g, Jump jump) {
  for (;;) {
    const int jx = jump.to & ((1 << shift_) - 1), jy = jump.to >> shift_;
    g += kStraight * (std::abs(jx - x) + std::abs(jy - y));
    if (jump.turn_x == 0 && jump.turn_y == 0) {
      relax(from, jump.to, g);
      return;
    }
    // Passed (or reached: the start) as cheaply already, this bend leads nowhere new.
    const int bend = jump.to;
    if (std::uint16_t(stamps_[bend] - generation_) < kStamps && nodes_[bend].g <= g) return;
    stamps_[bend] = std::uint16_t(generation_ + kBend);
    nodes_[bend] = Node{g, from};
    from = bend;
    x = jx;
    y = jy;
    jump = jumpStraight(x, y, jump.turn_x, jump.turn_y);
    if (jump.to < 0) return;
  }
}

[[gnu::always_inline]] inline void JumpPointSearch::relax(int from, int to, std::int64_t g) {
  const std::uint16_t stamp = stamps_[to];
  if (stamp == std::uint16_t(generation_ + kClosed)) return;
  if (stamp == std::uint16_t(generation_ + kOpen) && nodes_[to].g <= g) return;
  stamps_[to] = std::uint16_t(generation_ + kOpen);
  nodes_[to] = Node{g, from};
  const int tx = to & ((1 << shift_) - 1), ty = to >> shift_;
  open_.push(to, g, estimate(tx, ty));
  ++stats_.generated;
}

void JumpPointSearch::expand(int idx, int x, int y) {
  struct Direction {
    int dx, dy;
  };
  Direction dirs[8];
  int count = 0;
  const int parent = nodes_[idx].parent;
  if (parent < 0) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (dx != 0 || dy != 0) dirs[count++] = {dx, dy};
  } else {
    // The direction of the last move in: the canonical path from the parent runs diagonally
    // first, so it ends straight along the longer axis (diagonal when both are equal).
    const int ex = x - (parent & ((1 << shift_) - 1)), ey = y - (parent >> shift_);
    const int ax = std::abs(ex), ay = std::abs(ey);
    const int dx = ax >= ay ? sign(ex) : 0, dy = ay >= ax ? sign(ey) : 0;
    // Then the directions worth a jump: the one it came in on, a diagonal's two components,
    // and the forced neighbours of a straight move.
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
  const std::int64_t g = nodes_[idx].g;
  for (int k = 0; k < count; ++k) {
    const auto [dx, dy] = dirs[k];
    if (dx == 0 || dy == 0) {
      const Jump jump = jumpStraight(x, y, dx, dy);
      if (jump.to >= 0) relaxJump(idx, x, y, g, jump);
      continue;
    }
    // Along the diagonal, whatever the straight jumps from its cells reach is a successor.
    // Most straight jumps from a diagonal's cells end at a wall: those stay inline here.
    int cx = x, cy = y;
    while (stepDiagonal(cx, cy, dx, dy)) {
      const std::int64_t at = g + octileFixed(cx - x, cy - y);
      if (cx == goal_x_ && cy == goal_y_) {
        relax(idx, goal_idx_, at);
        break;
      }
      const Jump along_x = jumpStraight(cx, cy, dx, 0);
      if (along_x.to >= 0) relaxJump(idx, cx, cy, at, along_x);
      const Jump along_y = jumpStraight(cx, cy, 0, dy);
      if (along_y.to >= 0) relaxJump(idx, cx, cy, at, along_y);
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
  goal_idx_ = node(goal.x, goal.y);
  use_landmarks_ = landmarks_ != nullptr && landmarks_->validFor(map_);
  if (use_landmarks_) landmarks_->prepareGoal(goal.x, goal.y, goal_landmarks_);
  const std::uint16_t closed = std::uint16_t(generation_ + kClosed);
  const int start_idx = node(start.x, start.y);
  stamps_[start_idx] = std::uint16_t(generation_ + kOpen);
  nodes_[start_idx] = Node{0, -1};
  open_.push(start_idx, 0, estimate(start.x, start.y));
  ++stats_.generated;
  while (!open_.empty()) {
    const int idx = open_.pop().node;
    if (stamps_[idx] == closed) continue;  // an entry superseded by a cheaper one
    stamps_[idx] = closed;
    ++stats_.expanded;
    if (idx == goal_idx_) {
      tracePath(goal_idx_, out);
      return true;
    }
    expand(idx, idx & ((1 << shift_) - 1), idx >> shift_);
  }
  return false;
}

void JumpPointSearch::tracePath(int goal, GridPath& out) {
  corners_.clear();
  for (int i = goal; i >= 0; i = nodes_[i].parent) corners_.push_back(i);
  const int mask = (1 << shift_) - 1;
  out.cells.clear();
  Cell c{corners_.back() & mask, corners_.back() >> shift_};
  out.cells.push_back(c);
  // Each hop is the canonical path: diagonal while both axes differ, then straight.
  for (std::size_t k = corners_.size() - 1; k-- > 0;) {
    const Cell to{corners_[k] & mask, corners_[k] >> shift_};
    while (!(c == to)) {
      c.x += sign(to.x - c.x);
      c.y += sign(to.y - c.y);
      out.cells.push_back(c);
    }
  }
  out.length = pathLength(out.cells);
}

}  // namespace zonesim::ai
