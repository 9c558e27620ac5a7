#pragma once
// Waypoint graphs: points on the ground plane joined by weighted, directed edges that carry
// passability flags (door, water, ladder...). A query names the flags its agent may use; a
// door can also be shut on the edge itself. A* uses the straight-line distance scaled by the
// smallest cost-to-length ratio of any edge, so the heuristic stays admissible whatever the
// weights are.

#include <cstdint>
#include <vector>

#include "ai/spline_path.h"

namespace zonesim::ai {

/// A path through the graph: node ids from start to goal and its cost.
struct WaypointPath {
  std::vector<int> nodes;  ///< start first, goal last; empty when there is no path
  double cost = 0.0;       ///< sum of edge costs
};

/// Directed weighted graph of waypoints with a reusable A* searcher.
class WaypointGraph {
 public:
  /// Adds a waypoint and returns its id (ids are dense from 0).
  int addNode(Vec2 position);
  /// Adds an edge a -> b (and b -> a when `twoWay`); `flags` are what an agent needs to use it.
  /// Returns the id of the a -> b edge. Costs must be positive.
  int addEdge(int a, int b, double cost, std::uint32_t flags = 0, bool twoWay = true);
  /// Opens or shuts an edge (a door on it); shut edges are never used.
  void setEdgeOpen(int edge, bool open);
  /// Cheapest path using only edges whose flags are all in `allowed`; false when none.
  bool findPath(int start, int goal, std::uint32_t allowed, WaypointPath& out);
  /// Number of waypoints.
  int nodeCount() const { return int(positions_.size()); }
  /// Number of directed edges.
  int edgeCount() const { return int(edges_.size()); }

 private:
  struct Edge {
    int from;
    int to;
    double cost;
    std::uint32_t flags;
    bool open;
    int next;  // next edge out of `from`: adjacency lists without a rebuild step
  };
  struct Record {
    double g;
    int parent;
    std::uint32_t stamp;
  };
  struct HeapEntry {
    double f;
    double g;
    int idx;
  };

  std::vector<Vec2> positions_;
  std::vector<int> first_edge_;
  std::vector<Edge> edges_;
  double heuristic_scale_ = 1.0;
  std::vector<Record> records_;
  std::vector<HeapEntry> heap_;
  std::uint32_t generation_ = 0;
};

}  // namespace zonesim::ai
