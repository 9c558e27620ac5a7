#include "ai/grid_search.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "ai/fixed_cost.h"
#include "ai/open_order.h"
#include "ai/search_generation.h"

namespace zonesim::ai {

GridSearch::GridSearch(const GridMap& map)
    : map_(map), nodes_(std::size_t(map.width()) * std::size_t(map.height()), Node{0, -1, 0, -1}) {}

void GridSearch::beginSearch() {
  nextGeneration(generation_, nodes_);
  heap_.clear();
  stats_ = SearchStats{};
}

void GridSearch::siftUp(std::size_t i, const HeapEntry& e) {
  while (i > 0) {
    std::size_t parent = (i - 1) / 2;
    if (!popsBefore(e, heap_[parent])) break;
    heap_[i] = heap_[parent];
    nodes_[std::size_t(heap_[i].idx)].heap_pos = std::int32_t(i);
    i = parent;
  }
  heap_[i] = e;
  nodes_[std::size_t(e.idx)].heap_pos = std::int32_t(i);
}

void GridSearch::heapPush(const HeapEntry& e) {
  heap_.push_back(e);
  siftUp(heap_.size() - 1, e);
  ++stats_.generated;
}

void GridSearch::heapDecrease(const HeapEntry& e) {
  // A lower g for an open node lowers its f (same h) and only ever moves it up.
  siftUp(std::size_t(nodes_[std::size_t(e.idx)].heap_pos), e);
}

GridSearch::HeapEntry GridSearch::heapPop() {
  HeapEntry top = heap_.front();
  HeapEntry last = heap_.back();
  heap_.pop_back();
  std::size_t n = heap_.size();
  if (n == 0) return top;
  std::size_t i = 0;
  for (;;) {
    std::size_t child = 2 * i + 1;
    if (child >= n) break;
    if (child + 1 < n && popsBefore(heap_[child + 1], heap_[child])) ++child;
    if (!popsBefore(heap_[child], last)) break;
    heap_[i] = heap_[child];
    nodes_[std::size_t(heap_[i].idx)].heap_pos = std::int32_t(i);
    i = child;
  }
  heap_[i] = last;
  nodes_[std::size_t(last.idx)].heap_pos = std::int32_t(i);
  return top;
}

bool GridSearch::run(int start, int goal, const CellRect& bounds) {
  beginSearch();
  const std::uint32_t open = generation_, closed = generation_ + 1;
  const int w = map_.width();
  const Cell goalCell = goal >= 0 ? map_.cellAt(goal) : Cell{};
  const bool landmarks = goal >= 0 && landmarks_ != nullptr && landmarks_->validFor(map_);
  if (landmarks) landmarks_->prepareGoal(goalCell.x, goalCell.y, goal_landmarks_);
  auto heuristic = [&](int x, int y) {
    if (goal < 0) return std::int64_t(0);
    const std::int64_t octile = octileFixed(x - goalCell.x, y - goalCell.y);
    return landmarks ? std::max(octile, landmarks_->bound(x, y, goal_landmarks_)) : octile;
  };
  Cell s = map_.cellAt(start);
  nodes_[start] = Node{0, -1, open, -1};
  heapPush(HeapEntry{heuristic(s.x, s.y), 0, start});

  while (!heap_.empty()) {
    HeapEntry top = heapPop();
    Node& cur = nodes_[top.idx];
    cur.stamp = closed;
    ++stats_.expanded;
    if (top.idx == goal) return true;

    const int x = top.idx % w, y = top.idx / w;
    // Cardinal neighbours first; their openness also decides which diagonals are legal.
    static constexpr int kDx[4] = {1, -1, 0, 0};
    static constexpr int kDy[4] = {0, 0, 1, -1};
    bool free[4];
    auto relax = [&](int nx, int ny, std::int64_t cost) {
      int ni = ny * w + nx;
      Node& n = nodes_[ni];
      std::int64_t g = cur.g + cost;
      if (n.stamp == closed) return;
      if (n.stamp == open) {
        if (n.g <= g) return;
        n.g = g;
        n.parent = top.idx;
        heapDecrease(HeapEntry{g + heuristic(nx, ny), g, ni});
        return;
      }
      n = Node{g, top.idx, open, -1};
      heapPush(HeapEntry{g + heuristic(nx, ny), g, ni});
    };
    for (int d = 0; d < 4; ++d) {
      int nx = x + kDx[d], ny = y + kDy[d];
      free[d] = bounds.contains(nx, ny) && map_.passableAt(ny * w + nx);
      if (free[d]) relax(nx, ny, kStraight);
    }
    // A diagonal needs both cardinal cells beside it free (no corner cutting); those lie
    // inside `bounds` whenever both ends do, so the bounds check above covers them.
    for (int ix = 0; ix < 2; ++ix) {
      for (int iy = 2; iy < 4; ++iy) {
        if (!free[ix] || !free[iy]) continue;
        int nx = x + kDx[ix], ny = y + kDy[iy];
        if (map_.passableAt(ny * w + nx)) relax(nx, ny, kDiagonal);
      }
    }
  }
  return goal < 0;
}

bool GridSearch::findPath(Cell start, Cell goal, GridPath& out) {
  return findPath(start, goal, CellRect{0, 0, map_.width(), map_.height()}, out);
}

bool GridSearch::findPath(Cell start, Cell goal, const CellRect& bounds, GridPath& out) {
  out.clear();
  if (!bounds.contains(start.x, start.y) || !bounds.contains(goal.x, goal.y)) return false;
  if (!map_.passable(start.x, start.y) || !map_.passable(goal.x, goal.y)) return false;
  int g = map_.index(goal.x, goal.y);
  if (!run(map_.index(start.x, start.y), g, bounds)) return false;
  tracePath(g, out);
  return true;
}

void GridSearch::explore(Cell start, const CellRect& bounds) {
  if (!bounds.contains(start.x, start.y) || !map_.passable(start.x, start.y)) {
    beginSearch();  // nothing reached: distanceTo() answers "unreached" everywhere
    return;
  }
  run(map_.index(start.x, start.y), -1, bounds);
}

double GridSearch::distanceTo(Cell c) const {
  const std::int64_t cost = costTo(c);
  return cost >= 0 ? double(cost) / double(kStraight) : -1.0;
}

std::int64_t GridSearch::costTo(Cell c) const {
  if (!map_.inside(c.x, c.y)) return -1;
  const Node& n = nodes_[map_.index(c.x, c.y)];
  return n.stamp == generation_ + 1 ? n.g : -1;
}

void GridSearch::pathTo(Cell c, GridPath& out) const {
  out.clear();
  if (distanceTo(c) < 0) return;
  tracePath(map_.index(c.x, c.y), out);
}

void GridSearch::tracePath(int goal, GridPath& out) const {
  out.clear();
  for (int i = goal; i >= 0; i = nodes_[i].parent) out.cells.push_back(map_.cellAt(i));
  std::reverse(out.cells.begin(), out.cells.end());
  out.length = pathLength(out.cells);
}

}  // namespace zonesim::ai
