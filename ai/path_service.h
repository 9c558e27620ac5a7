#pragma once
// Path requests for many agents under a per-tick budget: requests queue in arrival order, each
// tick() plans at most `paths_per_tick` of them and stops once `expansions_per_tick` nodes were
// expanded (cache hits are free; at least one plan per tick so the queue always moves), so a
// burst of requests is spread over several ticks instead of blowing one. Map changes go through
// setCell(), which repairs the planner, invalidates cached paths and re-queues every request whose
// path it cut. The navmesh planner plans between cell centres (or exact points, solveBetween)
// and fills the path's cells with those its segments cross; a map change rebuilds its mesh.

#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "ai/grid_map.h"
#include "ai/grid_search.h"
#include "ai/hpa_planner.h"
#include "ai/jump_point_search.h"
#include "ai/landmark_heuristic.h"
#include "ai/navmesh.h"
#include "ai/navmesh_search.h"
#include "ai/path_cache.h"

namespace zonesim::ai {

/// Which planner serves requests.
enum class PlannerKind { AStar, Hpa, NavMesh, Jps };

/// Settings of a PathService.
struct PathServiceConfig {
  /// A* or jump point search (both optimal, the same lengths), HPA* (faster on large maps) or
  /// a navigation mesh.
  PlannerKind planner = PlannerKind::Hpa;
  HpaConfig hpa;                           ///< abstraction settings when planner is Hpa
  NavMeshConfig navmesh;                   ///< mesh settings when planner is NavMesh
  std::vector<NavBox> navmesh_boxes;       ///< static obstacles the mesh also closes
  int paths_per_tick = 8;                  ///< planner calls allowed per tick
  int expansions_per_tick = 0;             ///< node expansions allowed per tick (0: no limit)
  std::size_t cache_capacity = 1024;       ///< cached paths (0: no cache)
  /// Landmarks for the A* or jump point search estimate (ai/landmark_heuristic.h; 0: the
  /// octile distance alone). Built with the service and again at the first plan after the map
  /// changed.
  int landmarks = 0;
  /// Closing a cell clears the cache too. A kept path stays optimal, but a fresh plan on the new
  /// map may pick another path of the same length; set this where a hit must equal a fresh plan
  /// (zones, whose caches differ from rank to rank).
  bool clear_cache_on_close = false;
  /// Also plans every planned path again with plain A* (octile estimate) on the same map and
  /// keeps how much longer the planner's path is than that optimum (stats: audited,
  /// overhead_*): a measurement for tuning, which costs an A* search per plan and changes no
  /// path. The planner's own time (stats: plan_ns) leaves the audit out.
  bool audit = false;
};

/// State of a request.
enum class PathStatus { Unknown, Queued, Ready, NoPath };

/// Handle of a request: slot and a generation, so a released handle is never mistaken.
struct PathRequestId {
  std::uint32_t slot = 0;        ///< index into the request table
  std::uint32_t generation = 0;  ///< bumped when the slot is reused
};

/// Counters for reports and tests.
struct PathServiceStats {
  std::uint64_t planned = 0;     ///< planner calls
  std::uint64_t cache_hits = 0;  ///< requests served from the cache
  std::uint64_t replans = 0;     ///< requests re-queued because the map cut their path
  std::uint64_t expanded = 0;    ///< nodes expanded by all planner calls
  std::uint64_t landmark_builds = 0;  ///< landmark tables rebuilt after map changes
  std::int64_t plan_ns = 0;           ///< wall time in planner calls (audits left out)
  /// With config.audit: paths compared with the A* optimum between their end cells (for a
  /// navmesh path between exact points, with the straight line between them where that is
  /// longer), the sum and the largest of their overheads (length over the optimum, minus 1; 0
  /// for a path no longer than it, as an any-angle path can be).
  std::uint64_t audited = 0;
  double overhead_sum = 0.0;
  double overhead_max = 0.0;
  std::int64_t audit_ns = 0;  ///< wall time in those A* searches (what the audit adds to a tick)
};

/// Budgeted, cached path finding over one map that the service owns changes to.
class PathService {
 public:
  /// Serves paths on `map`, which must outlive the service and change only through setCell(), or
  /// by its owner followed by cellChanged().
  PathService(GridMap& map, const PathServiceConfig& config);

  /// Queues a request; its path is available after a later tick().
  PathRequestId request(Cell start, Cell goal);
  /// Forgets a request (its agent no longer needs the path).
  void release(PathRequestId id);
  /// Plans queued requests in arrival order within the per-tick budget.
  void tick();
  /// Plans one path now, outside the queue and its budget (for a caller that budgets itself):
  /// from the cache when it holds the pair, else by the planner (then cached). `expanded` is
  /// the planner's node count, on a hit the count stored with the path, so that with
  /// clear_cache_on_close a hit gives the caller's budget and the agent exactly what planning
  /// would.
  bool solve(Cell start, Cell goal, GridPath& out, int& expanded);
  /// As solve() between exact points in map units: the navmesh plans from `from` to `to`
  /// (never cached: points do not repeat), the grid planners between the cells holding them.
  /// False, as for a blocked cell, when an end is off the mesh.
  bool solveBetween(Vec2 from, Vec2 to, GridPath& out, int& expanded);
  /// Whether the navigation mesh covers the point (map units); false without a mesh.
  bool onMesh(Vec2 p) const { return mesh_ && mesh_->polygonAt(p) >= 0; }
  /// State of a request (Unknown for a released or stale handle).
  PathStatus status(PathRequestId id) const;
  /// The path of a Ready request (empty otherwise).
  const GridPath& path(PathRequestId id) const;
  /// Opens or closes a cell, repairs the planner, and re-queues requests whose path it cut.
  void setCell(Cell c, bool open);
  /// The same repairs for a cell its owner has already opened or closed on the shared map.
  void cellChanged(Cell c, bool open);
  /// Requests waiting for a tick.
  std::size_t queued() const { return queue_.size(); }
  /// Counters.
  PathServiceStats stats() const;

 private:
  struct Request {
    Cell start;
    Cell goal;
    PathStatus status = PathStatus::Unknown;
    std::uint32_t generation = 0;
    GridPath path;
  };

  const Request* find(PathRequestId id) const;
  bool plan(Cell start, Cell goal, GridPath& out, int& expanded);
  bool planOnMesh(Vec2 from, Vec2 to, GridPath& out, int& expanded);
  void rebuildMesh();
  void lendLandmarks(const LandmarkHeuristic* landmarks);  // to the grid planner in use
  // With config_.audit, after a found plan: `length` against the A* optimum from start to goal,
  // or against `straight` (the line between exact end points) where that is longer.
  void audit(Cell start, Cell goal, double length, double straight);

  GridMap& map_;
  PathServiceConfig config_;
  std::unique_ptr<GridSearch> astar_;
  std::unique_ptr<JumpPointSearch> jps_;
  std::unique_ptr<LandmarkHeuristic> landmarks_;  // A*, JPS or HPA*, when config_.landmarks > 0
  std::unique_ptr<HpaPlanner> hpa_;
  std::unique_ptr<NavMesh> mesh_;  // rebuilt whole on a map change
  std::unique_ptr<NavMeshSearch> mesh_search_;
  NavPath mesh_path_;
  std::vector<Cell> segment_cells_;
  PathCache cache_;
  std::vector<Request> requests_;
  std::vector<std::uint32_t> free_slots_;
  std::deque<PathRequestId> queue_;
  PathServiceStats stats_;
  GridPath empty_;
  std::unique_ptr<GridSearch> audit_search_;  // plain A*, no landmarks: the optimum
  GridPath audit_path_;
};

}  // namespace zonesim::ai
