#pragma once
// HPA* (Botea, Müller, Schaeffer 2004): the map is cut into square clusters; entrances on
// cluster borders become abstract nodes, joined by inter-cluster steps and by intra-cluster
// edges whose costs are optimal paths inside the cluster. A query links start and goal to their
// clusters' nodes, searches the small abstract graph, then refines each abstract edge with a
// search bounded to one cluster. Paths are near-optimal; the overhead is measured, not assumed.
// Smoothing (on by default) re-plans windows of a few abstract steps with A* bounded to the
// window's bounding box, which can only shorten the path and keeps it on the 8-connected grid.

#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "ai/grid_path.h"
#include "ai/grid_search.h"
#include "ai/jump_point_search.h"
#include "ai/landmark_heuristic.h"

namespace zonesim::ai {

/// Settings of the abstraction.
struct HpaConfig {
  int cluster_size = 16;  ///< cluster side in cells
  int wide_entrance = 6;  ///< entrances at least this wide get a transition at each end
  /// Re-optimise windows of this many abstract steps (0: raw HPA*). 8 brings the random map's
  /// mean overhead from 2.8 % to 0.8 % (worst 10.0 to 5.7 %) for about 7 % more time there;
  /// on the rooms it doubles the time, still 5x faster than A* (docs/benchmarks.md).
  int smooth_span = 8;
  /// Queries whose ends are at most this far apart (octile cells) go to an optimal jump point
  /// search instead: short paths are where the abstraction costs more than it saves and
  /// where its detours are largest relative to the path. Negative: always through the
  /// abstraction.
  double direct_distance = 64.0;
};

/// Size of the abstraction, for reports.
struct HpaStats {
  int clusters = 0;       ///< number of clusters
  int nodes = 0;          ///< abstract nodes (transition cells)
  int edges = 0;          ///< directed abstract edges
  int expanded = 0;       ///< abstract nodes expanded by the last query
  int grid_expanded = 0;  ///< grid cells expanded by the last query (linking, refining, smoothing)
  bool direct = false;    ///< the last query was answered by the direct optimal search
};

/// Hierarchical planner over a map that may change; repairs only the clusters a change touches.
class HpaPlanner {
 public:
  /// Builds the abstraction of `map`, which must outlive the planner.
  HpaPlanner(const GridMap& map, const HpaConfig& config);

  /// A near-optimal path; false (and `out` empty) when start and goal are not connected.
  bool findPath(Cell start, Cell goal, GridPath& out);
  /// Repairs the clusters around a cell that was opened or closed (call after changing it).
  void cellChanged(Cell c);
  /// Rebuilds the whole abstraction (a query does this itself after unreported changes).
  void rebuild();
  /// Size of the abstraction and work of the last query.
  HpaStats stats() const;
  /// Estimates costs with `landmarks` as well (may be null; must outlive the planner, and is
  /// used only while valid for the map): the abstract search, the searches that link and
  /// refine, and the direct jump point search. Costs stay optimal where they were; a query
  /// expands fewer nodes where the walls mislead the octile distance.
  void useLandmarks(const LandmarkHeuristic* landmarks);

 private:
  struct Transition {
    std::int32_t a;  // cell on the left/top side
    std::int32_t b;  // cell on the right/bottom side
  };
  struct IntraEdge {
    std::int32_t a;
    std::int32_t b;
    double cost;
  };
  struct Edge {
    std::int32_t to;
    double cost;
  };
  struct AbstractNode {
    double g;
    std::int32_t parent;
    std::uint32_t stamp;
  };
  struct HeapEntry {
    double f;
    double g;
    std::int32_t idx;
  };

  int clusterOf(int x, int y) const;
  CellRect clusterRect(int cluster) const;
  void scanBorder(int border);
  void clusterNodeCells(int cluster, std::vector<std::int32_t>& out) const;
  void computeIntraEdges(int cluster);
  void assembleGraph();
  bool searchAbstract(int startNode, int goalNode, Cell goal);
  void smooth(GridPath& out);

  const GridMap& map_;
  HpaConfig config_;
  const LandmarkHeuristic* landmarks_ = nullptr;
  LandmarkHeuristic::Goal goal_landmarks_;  // kept to avoid allocating per query
  int clusters_x_ = 0, clustersY_ = 0;
  // Borders: first the vertical ones (between (cx, cy) and (cx + 1, cy)), then horizontal.
  std::vector<std::vector<Transition>> borders_;
  std::vector<std::vector<IntraEdge>> intra_;
  // Abstract graph in compressed rows; node i is cell node_cell_[i].
  std::vector<std::int32_t> node_cell_;
  std::vector<std::int32_t> cell_node_;
  std::vector<std::int32_t> edge_start_;
  std::vector<Edge> edges_;
  std::uint64_t built_version_ = 0;

  // Per-query scratch, reused so that a warmed-up query allocates only for its path.
  GridSearch search_;
  JumpPointSearch direct_search_;
  bool last_direct_ = false;
  std::vector<Edge> start_edges_;
  std::vector<double> goal_cost_;
  std::vector<std::uint32_t> goal_stamp_;
  std::vector<AbstractNode> records_;
  std::vector<HeapEntry> heap_;
  std::vector<std::int32_t> abstract_path_;
  std::vector<std::int32_t> scratch_cells_;
  GridPath piece_;
  GridPath direct_;
  std::vector<std::int32_t> waypoints_;  // positions in the refined path of abstract nodes
  std::vector<Cell> smoothed_;
  std::uint32_t generation_ = 0;
  int expanded_ = 0;
  int grid_expanded_ = 0;
};

}  // namespace zonesim::ai
