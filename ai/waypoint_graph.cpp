#include "ai/waypoint_graph.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "ai/open_order.h"

namespace zonesim::ai {

int WaypointGraph::addNode(Vec2 position) {
  positions_.push_back(position);
  first_edge_.push_back(-1);
  records_.push_back(Record{0.0, -1, 0});
  return int(positions_.size()) - 1;
}

int WaypointGraph::addEdge(int a, int b, double cost, std::uint32_t flags, bool twoWay) {
  assert(a >= 0 && a < nodeCount() && b >= 0 && b < nodeCount() && cost > 0);
  double length = std::hypot(positions_[std::size_t(b)].x - positions_[std::size_t(a)].x,
                             positions_[std::size_t(b)].y - positions_[std::size_t(a)].y);
  // An edge cheaper than its straight-line length would make the plain distance inadmissible.
  if (length > 0) heuristic_scale_ = std::min(heuristic_scale_, cost / length);
  auto add = [&](int from, int to) {
    edges_.push_back(Edge{from, to, cost, flags, true, first_edge_[std::size_t(from)]});
    first_edge_[std::size_t(from)] = int(edges_.size()) - 1;
    return int(edges_.size()) - 1;
  };
  int id = add(a, b);
  if (twoWay) add(b, a);
  return id;
}

void WaypointGraph::setEdgeOpen(int edge, bool open) {
  edges_[std::size_t(edge)].open = open;
}

bool WaypointGraph::findPath(int start, int goal, std::uint32_t allowed, WaypointPath& out) {
  out.nodes.clear();
  out.cost = 0.0;
  if (start < 0 || goal < 0 || start >= nodeCount() || goal >= nodeCount()) return false;
  if (generation_ >= 0xFFFFFFF0u) {
    for (Record& r : records_) r.stamp = 0;
    generation_ = 0;
  }
  generation_ += 2;
  const std::uint32_t open = generation_, closed = generation_ + 1;
  const Vec2 target = positions_[std::size_t(goal)];
  auto h = [&](int n) {
    const Vec2 p = positions_[std::size_t(n)];
    return heuristic_scale_ * std::hypot(target.x - p.x, target.y - p.y);
  };
  constexpr PopsLater cmp{};
  heap_.clear();
  records_[std::size_t(start)] = Record{0.0, -1, open};
  heap_.push_back(HeapEntry{h(start), 0.0, start});
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), cmp);
    HeapEntry top = heap_.back();
    heap_.pop_back();
    Record& cur = records_[std::size_t(top.idx)];
    if (cur.stamp == closed || top.g > cur.g) continue;
    cur.stamp = closed;
    if (top.idx == goal) {
      out.cost = cur.g;
      for (int n = goal; n >= 0; n = records_[std::size_t(n)].parent) out.nodes.push_back(n);
      std::reverse(out.nodes.begin(), out.nodes.end());
      return true;
    }
    for (int e = first_edge_[std::size_t(top.idx)]; e >= 0; e = edges_[std::size_t(e)].next) {
      const Edge& edge = edges_[std::size_t(e)];
      if (!edge.open || (edge.flags & ~allowed) != 0) continue;
      Record& next = records_[std::size_t(edge.to)];
      double g = cur.g + edge.cost;
      if (next.stamp == closed || (next.stamp == open && next.g <= g)) continue;
      next = Record{g, top.idx, open};
      heap_.push_back(HeapEntry{g + h(edge.to), g, edge.to});
      std::push_heap(heap_.begin(), heap_.end(), cmp);
    }
  }
  return false;
}

}  // namespace zonesim::ai
