#include "ai/hpa_planner.h"

#include <algorithm>
#include <cassert>

#include "ai/fixed_cost.h"
#include "ai/open_order.h"

namespace zonesim::ai {

HpaPlanner::HpaPlanner(const GridMap& map, const HpaConfig& config)
    : map_(map), config_(config), search_(map), direct_search_(map) {
  assert(config_.cluster_size >= 2);
  clusters_x_ = (map_.width() + config_.cluster_size - 1) / config_.cluster_size;
  clustersY_ = (map_.height() + config_.cluster_size - 1) / config_.cluster_size;
  borders_.resize(std::size_t((clusters_x_ - 1) * clustersY_ + clusters_x_ * (clustersY_ - 1)));
  intra_.resize(std::size_t(clusters_x_ * clustersY_));
  cell_node_.assign(std::size_t(map_.width()) * std::size_t(map_.height()), -1);
  rebuild();
}

int HpaPlanner::clusterOf(int x, int y) const {
  return (y / config_.cluster_size) * clusters_x_ + x / config_.cluster_size;
}

CellRect HpaPlanner::clusterRect(int cluster) const {
  int cx = cluster % clusters_x_, cy = cluster / clusters_x_, c = config_.cluster_size;
  return CellRect{cx * c, cy * c, std::min((cx + 1) * c, map_.width()),
                  std::min((cy + 1) * c, map_.height())};
}

void HpaPlanner::scanBorder(int border) {
  const int vertical = (clusters_x_ - 1) * clustersY_;
  const int c = config_.cluster_size;
  // The border as a line of cell pairs (a on the left/top side, b across it).
  int ax, ay, stepX, stepY, bx, by, length;
  if (border < vertical) {
    int cx = border % (clusters_x_ - 1), cy = border / (clusters_x_ - 1);
    ax = (cx + 1) * c - 1, ay = cy * c, bx = 1, by = 0, stepX = 0, stepY = 1;
    length = std::min((cy + 1) * c, map_.height()) - ay;
  } else {
    int h = border - vertical;
    int cx = h % clusters_x_, cy = h / clusters_x_;
    ax = cx * c, ay = (cy + 1) * c - 1, bx = 0, by = 1, stepX = 1, stepY = 0;
    length = std::min((cx + 1) * c, map_.width()) - ax;
  }
  auto& out = borders_[std::size_t(border)];
  out.clear();
  auto open = [&](int i) {
    int x = ax + i * stepX, y = ay + i * stepY;
    return map_.passable(x, y) && map_.passable(x + bx, y + by);
  };
  auto add = [&](int i) {
    int x = ax + i * stepX, y = ay + i * stepY;
    out.push_back(Transition{map_.index(x, y), map_.index(x + bx, y + by)});
  };
  for (int i = 0; i < length;) {
    if (!open(i)) {
      ++i;
      continue;
    }
    int first = i;
    while (i < length && open(i)) ++i;
    int run = i - first;
    // Narrow entrances get one transition in the middle, wide ones one at each end, so that
    // paths hugging either wall do not detour through the middle.
    if (run < config_.wide_entrance) {
      add(first + run / 2);
    } else {
      add(first);
      add(i - 1);
    }
  }
}

void HpaPlanner::clusterNodeCells(int cluster, std::vector<std::int32_t>& out) const {
  out.clear();
  const int vertical = (clusters_x_ - 1) * clustersY_;
  int cx = cluster % clusters_x_, cy = cluster / clusters_x_;
  auto take = [&](int border, bool sideA) {
    for (const Transition& t : borders_[std::size_t(border)]) out.push_back(sideA ? t.a : t.b);
  };
  if (cx > 0) take(cy * (clusters_x_ - 1) + cx - 1, false);
  if (cx < clusters_x_ - 1) take(cy * (clusters_x_ - 1) + cx, true);
  if (cy > 0) take(vertical + (cy - 1) * clusters_x_ + cx, false);
  if (cy < clustersY_ - 1) take(vertical + cy * clusters_x_ + cx, true);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

void HpaPlanner::computeIntraEdges(int cluster) {
  auto& edges = intra_[std::size_t(cluster)];
  edges.clear();
  clusterNodeCells(cluster, scratch_cells_);
  const CellRect rect = clusterRect(cluster);
  for (std::size_t i = 0; i + 1 < scratch_cells_.size(); ++i) {
    search_.explore(map_.cellAt(scratch_cells_[i]), rect);
    for (std::size_t j = i + 1; j < scratch_cells_.size(); ++j) {
      double d = search_.distanceTo(map_.cellAt(scratch_cells_[j]));
      if (d >= 0) edges.push_back(IntraEdge{scratch_cells_[i], scratch_cells_[j], d});
    }
  }
}

void HpaPlanner::assembleGraph() {
  for (std::int32_t cell : node_cell_) cell_node_[std::size_t(cell)] = -1;
  node_cell_.clear();
  for (const auto& border : borders_) {
    for (const Transition& t : border) {
      node_cell_.push_back(t.a);
      node_cell_.push_back(t.b);
    }
  }
  std::sort(node_cell_.begin(), node_cell_.end());
  node_cell_.erase(std::unique(node_cell_.begin(), node_cell_.end()), node_cell_.end());
  const int n = int(node_cell_.size());
  for (int i = 0; i < n; ++i) cell_node_[std::size_t(node_cell_[std::size_t(i)])] = i;

  // Two passes over the same edge list: count degrees, then fill rows in a fixed order.
  auto forEachEdge = [&](auto&& emit) {
    for (const auto& border : borders_) {
      for (const Transition& t : border) {
        emit(cell_node_[std::size_t(t.a)], cell_node_[std::size_t(t.b)], 1.0);
      }
    }
    for (const auto& edges : intra_) {
      for (const IntraEdge& e : edges) {
        emit(cell_node_[std::size_t(e.a)], cell_node_[std::size_t(e.b)], e.cost);
      }
    }
  };
  edge_start_.assign(std::size_t(n) + 1, 0);
  forEachEdge([&](int a, int b, double) {
    ++edge_start_[std::size_t(a) + 1];
    ++edge_start_[std::size_t(b) + 1];
  });
  for (int i = 0; i < n; ++i) edge_start_[std::size_t(i) + 1] += edge_start_[std::size_t(i)];
  edges_.resize(std::size_t(edge_start_[std::size_t(n)]));
  std::vector<std::int32_t> fill(edge_start_.begin(), edge_start_.end() - 1);
  forEachEdge([&](int a, int b, double cost) {
    edges_[std::size_t(fill[std::size_t(a)]++)] = Edge{b, cost};
    edges_[std::size_t(fill[std::size_t(b)]++)] = Edge{a, cost};
  });

  // Two extra records for the query's start and goal.
  records_.resize(std::size_t(n) + 2, AbstractNode{0.0, -1, 0});
  goal_cost_.resize(std::size_t(n), 0.0);
  goal_stamp_.resize(std::size_t(n), 0);
  built_version_ = map_.version();
}

void HpaPlanner::rebuild() {
  for (int b = 0; b < int(borders_.size()); ++b) scanBorder(b);
  for (int k = 0; k < clusters_x_ * clustersY_; ++k) computeIntraEdges(k);
  assembleGraph();
}

void HpaPlanner::cellChanged(Cell c) {
  const int size = config_.cluster_size;
  const int vertical = (clusters_x_ - 1) * clustersY_;
  const int cx = c.x / size, cy = c.y / size, k = clusterOf(c.x, c.y);
  const CellRect r = clusterRect(k);
  // A cell on a cluster edge can change that border's entrances and so the neighbour's nodes.
  int dirty[3] = {k, -1, -1};
  int ndirty = 1;
  if (c.x == r.x0 && cx > 0) {
    scanBorder(cy * (clusters_x_ - 1) + cx - 1);
    dirty[ndirty++] = k - 1;
  } else if (c.x == r.x1 - 1 && cx < clusters_x_ - 1) {
    scanBorder(cy * (clusters_x_ - 1) + cx);
    dirty[ndirty++] = k + 1;
  }
  if (c.y == r.y0 && cy > 0) {
    scanBorder(vertical + (cy - 1) * clusters_x_ + cx);
    dirty[ndirty++] = k - clusters_x_;
  } else if (c.y == r.y1 - 1 && cy < clustersY_ - 1) {
    scanBorder(vertical + cy * clusters_x_ + cx);
    dirty[ndirty++] = k + clusters_x_;
  }
  for (int i = 0; i < ndirty; ++i) computeIntraEdges(dirty[i]);
  assembleGraph();
}

HpaStats HpaPlanner::stats() const {
  return HpaStats{clusters_x_ * clustersY_, int(node_cell_.size()),
                  int(edges_.size()),       expanded_,
                  grid_expanded_,           last_direct_};
}

void HpaPlanner::useLandmarks(const LandmarkHeuristic* landmarks) {
  landmarks_ = landmarks;
  search_.useLandmarks(landmarks);
  direct_search_.useLandmarks(landmarks);
}

bool HpaPlanner::searchAbstract(int startNode, int goalNode, Cell goal) {
  const std::uint32_t open = generation_, closed = generation_ + 1;
  auto cellOf = [&](int node) {
    return node < int(node_cell_.size()) ? map_.cellAt(node_cell_[std::size_t(node)]) : goal;
  };
  auto push = [&](const HeapEntry& e) {
    heap_.push_back(e);
    std::push_heap(heap_.begin(), heap_.end(), PopsLater{});
  };
  // Abstract edges cost at least the grid distance they span, so a lower bound on the grid
  // distance to the goal is a consistent estimate here too. The landmarks' fixed-point bound
  // is scaled back to cells (its rounding is far below any difference of two path costs).
  const bool landmarks = landmarks_ != nullptr && landmarks_->validFor(map_);
  if (landmarks) landmarks_->prepareGoal(goal.x, goal.y, goal_landmarks_);
  auto estimate = [&](Cell c) {
    const double octile = octileDistance(c, goal);
    if (!landmarks) return octile;
    return std::max(octile,
                    double(landmarks_->bound(c.x, c.y, goal_landmarks_)) / double(kStraight));
  };
  heap_.clear();
  records_[std::size_t(startNode)] = AbstractNode{0.0, -1, open};
  records_[std::size_t(goalNode)].stamp = 0;
  push(HeapEntry{0.0, 0.0, startNode});
  auto relax = [&](int from, int to, double cost) {
    AbstractNode& n = records_[std::size_t(to)];
    double g = records_[std::size_t(from)].g + cost;
    if (n.stamp == closed || (n.stamp == open && n.g <= g)) return;
    n = AbstractNode{g, from, open};
    push(HeapEntry{g + (to == goalNode ? 0.0 : estimate(cellOf(to))), g, to});
  };
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), PopsLater{});
    HeapEntry top = heap_.back();
    heap_.pop_back();
    AbstractNode& cur = records_[std::size_t(top.idx)];
    if (cur.stamp == closed || top.g > cur.g) continue;
    cur.stamp = closed;
    ++expanded_;
    if (top.idx == goalNode) return true;
    if (top.idx == startNode) {
      for (const Edge& e : start_edges_) relax(startNode, e.to, e.cost);
      continue;
    }
    const std::size_t u = std::size_t(top.idx);
    for (std::int32_t i = edge_start_[u]; i < edge_start_[u + 1]; ++i) {
      relax(top.idx, edges_[std::size_t(i)].to, edges_[std::size_t(i)].cost);
    }
    if (goal_stamp_[u] == generation_) relax(top.idx, goalNode, goal_cost_[u]);
  }
  return false;
}

bool HpaPlanner::findPath(Cell start, Cell goal, GridPath& out) {
  out.clear();
  expanded_ = 0;
  grid_expanded_ = 0;
  last_direct_ = false;
  if (!map_.passable(start.x, start.y) || !map_.passable(goal.x, goal.y)) return false;
  if (octileDistance(start, goal) <= config_.direct_distance) {
    last_direct_ = true;
    const bool found = direct_search_.findPath(start, goal, out);
    grid_expanded_ = direct_search_.lastStats().expanded;
    return found;
  }
  if (map_.version() != built_version_) rebuild();
  if (start == goal) {
    out.cells.push_back(start);
    return true;
  }
  if (generation_ >= 0xFFFFFFF0u) {
    for (auto& r : records_) r.stamp = 0;
    std::fill(goal_stamp_.begin(), goal_stamp_.end(), 0u);
    generation_ = 0;
  }
  generation_ += 2;

  const int n = int(node_cell_.size());
  const int startNode = n, goalNode = n + 1;
  const int startCluster = clusterOf(start.x, start.y), goalCluster = clusterOf(goal.x, goal.y);

  // Link the goal, then the start, to the abstract nodes of their clusters.
  clusterNodeCells(goalCluster, scratch_cells_);
  search_.explore(goal, clusterRect(goalCluster));
  grid_expanded_ += search_.lastStats().expanded;
  for (std::int32_t cell : scratch_cells_) {
    double d = search_.distanceTo(map_.cellAt(cell));
    if (d < 0) continue;
    int node = cell_node_[std::size_t(cell)];
    goal_cost_[std::size_t(node)] = d;
    goal_stamp_[std::size_t(node)] = generation_;
  }
  clusterNodeCells(startCluster, scratch_cells_);
  search_.explore(start, clusterRect(startCluster));
  grid_expanded_ += search_.lastStats().expanded;
  start_edges_.clear();
  for (std::int32_t cell : scratch_cells_) {
    double d = search_.distanceTo(map_.cellAt(cell));
    if (d >= 0) start_edges_.push_back(Edge{cell_node_[std::size_t(cell)], d});
  }

  // Within one cluster the bounded search may beat any route through the borders, or be the
  // only one (a cluster with no entrances).
  bool haveDirect = startCluster == goalCluster &&
                    search_.findPath(start, goal, clusterRect(startCluster), direct_);
  if (startCluster == goalCluster) grid_expanded_ += search_.lastStats().expanded;
  bool haveAbstract = searchAbstract(startNode, goalNode, goal);
  if (haveDirect && (!haveAbstract || direct_.length <= records_[std::size_t(goalNode)].g)) {
    out.cells = direct_.cells;
    out.length = direct_.length;
    return true;
  }
  if (!haveAbstract) return false;

  abstract_path_.clear();
  for (int v = goalNode; v >= 0; v = records_[std::size_t(v)].parent) abstract_path_.push_back(v);
  std::reverse(abstract_path_.begin(), abstract_path_.end());
  auto cellOfNode = [&](int node) {
    if (node == startNode) return start;
    if (node == goalNode) return goal;
    return map_.cellAt(node_cell_[std::size_t(node)]);
  };
  out.cells.push_back(start);
  waypoints_.assign(1, 0);
  for (std::size_t i = 1; i < abstract_path_.size(); ++i) {
    Cell a = cellOfNode(abstract_path_[i - 1]), b = cellOfNode(abstract_path_[i]);
    int ka = clusterOf(a.x, a.y);
    if (ka != clusterOf(b.x, b.y)) {
      out.cells.push_back(b);  // an inter-cluster step across a border
      waypoints_.push_back(std::int32_t(out.cells.size()) - 1);
      continue;
    }
    if (a == b) continue;
    bool ok = search_.findPath(a, b, clusterRect(ka), piece_);
    grid_expanded_ += search_.lastStats().expanded;
    assert(ok && "an abstract edge must refine inside its cluster");
    if (!ok) {
      out.clear();
      return false;
    }
    out.cells.insert(out.cells.end(), piece_.cells.begin() + 1, piece_.cells.end());
    waypoints_.push_back(std::int32_t(out.cells.size()) - 1);
  }
  if (config_.smooth_span > 0) smooth(out);
  out.length = pathLength(out.cells);
  return true;
}

void HpaPlanner::smooth(GridPath& out) {
  smoothed_.clear();
  smoothed_.push_back(out.cells.front());
  const std::size_t last = waypoints_.size() - 1;
  for (std::size_t k = 0; k < last; k += std::size_t(config_.smooth_span)) {
    const std::size_t a = std::size_t(waypoints_[k]);
    const std::size_t b =
        std::size_t(waypoints_[std::min(k + std::size_t(config_.smooth_span), last)]);
    // The window's box holds the current sub-path, so the bounded optimum is never longer.
    CellRect box{out.cells[a].x, out.cells[a].y, out.cells[a].x + 1, out.cells[a].y + 1};
    for (std::size_t i = a + 1; i <= b; ++i) {
      box.x0 = std::min(box.x0, out.cells[i].x);
      box.y0 = std::min(box.y0, out.cells[i].y);
      box.x1 = std::max(box.x1, out.cells[i].x + 1);
      box.y1 = std::max(box.y1, out.cells[i].y + 1);
    }
    bool found = search_.findPath(out.cells[a], out.cells[b], box, piece_);
    grid_expanded_ += search_.lastStats().expanded;
    if (found) {
      smoothed_.insert(smoothed_.end(), piece_.cells.begin() + 1, piece_.cells.end());
    } else {
      smoothed_.insert(smoothed_.end(), out.cells.begin() + std::ptrdiff_t(a) + 1,
                       out.cells.begin() + std::ptrdiff_t(b) + 1);
    }
  }
  out.cells.swap(smoothed_);
}

}  // namespace zonesim::ai
