#include "ai/path_service.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ai/segment_cells.h"
#include "common/timer.h"

namespace zonesim::ai {

PathService::PathService(GridMap& map, const PathServiceConfig& config)
    : map_(map), config_(config), cache_(config.cache_capacity) {
  if (config_.landmarks != 0 && config_.planner == PlannerKind::NavMesh)
    throw std::invalid_argument("path service: landmarks serve the A*, JPS and HPA* planners only");
  if (config_.planner == PlannerKind::AStar) {
    astar_ = std::make_unique<GridSearch>(map_);
  } else if (config_.planner == PlannerKind::Jps) {
    jps_ = std::make_unique<JumpPointSearch>(map_, JumpPointSearch::Jumps::Scanned);
  } else if (config_.planner == PlannerKind::Hpa) {
    hpa_ = std::make_unique<HpaPlanner>(map_, config_.hpa);
  } else {
    rebuildMesh();
  }
  if (config_.landmarks != 0) {
    landmarks_ = std::make_unique<LandmarkHeuristic>(map_, config_.landmarks);
    lendLandmarks(landmarks_.get());
  }
}

void PathService::lendLandmarks(const LandmarkHeuristic* landmarks) {
  if (astar_) astar_->useLandmarks(landmarks);
  if (jps_) jps_->useLandmarks(landmarks);
  if (hpa_) hpa_->useLandmarks(landmarks);
}

void PathService::rebuildMesh() {
  mesh_search_.reset();
  mesh_ = std::make_unique<NavMesh>(map_, config_.navmesh_boxes, config_.navmesh);
  mesh_search_ = std::make_unique<NavMeshSearch>(*mesh_);
}

bool PathService::planOnMesh(Vec2 from, Vec2 to, GridPath& out, int& expanded) {
  out.clear();
  expanded = 0;
  if (mesh_->polygonAt(from) < 0 || mesh_->polygonAt(to) < 0) return false;
  const bool found = mesh_search_->findPath(from, to, mesh_path_);
  expanded = mesh_search_->lastExpanded();
  if (!found) return false;
  out.points = mesh_path_.points;
  out.length = mesh_path_.length;
  auto add = [&](Cell c) {
    if (out.cells.empty() || !(out.cells.back() == c)) out.cells.push_back(c);
  };
  add(Cell{int(std::floor(from.x)), int(std::floor(from.y))});
  for (std::size_t k = 1; k < out.points.size(); ++k) {
    // Every cell the segment touches (closing any of them may cut it), in column order, then
    // sorted along the segment so the cells run from start to goal.
    segment_cells_.clear();
    forEachCellMet(out.points[k - 1], out.points[k], CellContact::Closed,
                   [&](Cell c) { segment_cells_.push_back(c); });
    const Vec2 a = out.points[k - 1], b = out.points[k];
    auto along = [&](Cell c) {
      return (c.x + 0.5 - a.x) * (b.x - a.x) + (c.y + 0.5 - a.y) * (b.y - a.y);
    };
    std::stable_sort(segment_cells_.begin(), segment_cells_.end(),
                     [&](Cell l, Cell r) { return along(l) < along(r); });
    for (Cell c : segment_cells_) add(c);
  }
  add(Cell{int(std::floor(to.x)), int(std::floor(to.y))});
  return true;
}

bool PathService::solveBetween(Vec2 from, Vec2 to, GridPath& out, int& expanded) {
  if (!mesh_) {
    return solve(Cell{int(std::floor(from.x)), int(std::floor(from.y))},
                 Cell{int(std::floor(to.x)), int(std::floor(to.y))}, out, expanded);
  }
  ++stats_.planned;
  const std::int64_t started = nowNs();
  const bool found = planOnMesh(from, to, out, expanded);
  stats_.plan_ns += nowNs() - started;
  stats_.expanded += std::uint64_t(expanded);
  // Between exact points the grid optimum runs between the end cells' centres, which can be
  // shorter than the straight line between the points themselves (neighbouring cells, points
  // at their far sides): the path is then measured against that line.
  if (found && config_.audit)
    audit(Cell{int(std::floor(from.x)), int(std::floor(from.y))},
          Cell{int(std::floor(to.x)), int(std::floor(to.y))}, out.length,
          std::hypot(to.x - from.x, to.y - from.y));
  return found;
}

void PathService::audit(Cell start, Cell goal, double length, double straight) {
  const std::int64_t started = nowNs();
  if (!audit_search_) audit_search_ = std::make_unique<GridSearch>(map_);
  const bool found = audit_search_->findPath(start, goal, audit_path_);
  stats_.audit_ns += nowNs() - started;
  if (!found) return;
  const double optimum = std::max(audit_path_.length, straight);
  if (!(optimum > 0)) return;
  const double overhead = std::max(0.0, length / optimum - 1.0);
  ++stats_.audited;
  stats_.overhead_sum += overhead;
  stats_.overhead_max = std::max(stats_.overhead_max, overhead);
}

PathRequestId PathService::request(Cell start, Cell goal) {
  std::uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    slot = std::uint32_t(requests_.size());
    requests_.emplace_back();
  }
  Request& r = requests_[slot];
  r.start = start;
  r.goal = goal;
  r.status = PathStatus::Queued;
  r.path.clear();
  PathRequestId id{slot, r.generation};
  queue_.push_back(id);
  return id;
}

void PathService::release(PathRequestId id) {
  if (!find(id)) return;
  Request& r = requests_[id.slot];
  r.status = PathStatus::Unknown;
  r.path.clear();
  ++r.generation;  // stale handles, including any left in the queue, no longer match
  free_slots_.push_back(id.slot);
}

const PathService::Request* PathService::find(PathRequestId id) const {
  if (id.slot >= requests_.size()) return nullptr;
  const Request& r = requests_[id.slot];
  return r.generation == id.generation && r.status != PathStatus::Unknown ? &r : nullptr;
}

bool PathService::plan(Cell start, Cell goal, GridPath& out, int& expanded) {
  ++stats_.planned;
  const std::int64_t started = nowNs();
  bool found;
  if (landmarks_ && !landmarks_->validFor(map_)) {
    // Rebuilt here rather than on each change: a tick's doors cost one rebuild, and the
    // table always matches the map the plan sees (so every rank plans alike).
    // The old table goes first: two at once would double the memory for a moment.
    lendLandmarks(nullptr);
    landmarks_.reset();
    landmarks_ = std::make_unique<LandmarkHeuristic>(map_, config_.landmarks);
    lendLandmarks(landmarks_.get());
    ++stats_.landmark_builds;
  }
  if (jps_) {
    found = jps_->findPath(start, goal, out);
    expanded = jps_->lastStats().expanded;
  } else if (astar_) {
    found = astar_->findPath(start, goal, out);
    expanded = astar_->lastStats().expanded;
  } else if (mesh_) {
    found = planOnMesh(Vec2{start.x + 0.5, start.y + 0.5}, Vec2{goal.x + 0.5, goal.y + 0.5}, out,
                       expanded);
  } else {
    found = hpa_->findPath(start, goal, out);
    expanded = hpa_->stats().expanded + hpa_->stats().grid_expanded;
  }
  stats_.plan_ns += nowNs() - started;
  stats_.expanded += std::uint64_t(expanded);
  if (found && config_.audit) audit(start, goal, out.length, 0.0);
  return found;
}

void PathService::tick() {
  int budget = config_.paths_per_tick;
  long expansions = 0;
  bool plannedAny = false;
  while (!queue_.empty()) {
    PathRequestId id = queue_.front();
    const Request* found = find(id);
    if (!found || found->status != PathStatus::Queued) {
      queue_.pop_front();  // released, or already served by an earlier entry
      continue;
    }
    Request& r = requests_[id.slot];
    if (const GridPath* cached = cache_.find(r.start, r.goal)) {
      r.path = *cached;
      r.status = PathStatus::Ready;
      ++stats_.cache_hits;
      queue_.pop_front();
      continue;
    }
    if (budget == 0) break;
    if (plannedAny && config_.expansions_per_tick > 0 &&
        expansions >= config_.expansions_per_tick) {
      break;
    }
    --budget;
    plannedAny = true;
    queue_.pop_front();
    int expanded = 0;
    bool ok = plan(r.start, r.goal, r.path, expanded);
    expansions += expanded;
    if (ok) {
      r.status = PathStatus::Ready;
      cache_.insert(r.start, r.goal, r.path, expanded);
    } else {
      r.status = PathStatus::NoPath;
    }
  }
}

bool PathService::solve(Cell start, Cell goal, GridPath& out, int& expanded) {
  if (const GridPath* cached = cache_.find(start, goal, &expanded)) {
    out = *cached;
    ++stats_.cache_hits;
    return true;
  }
  if (!plan(start, goal, out, expanded)) return false;
  cache_.insert(start, goal, out, expanded);
  return true;
}

PathStatus PathService::status(PathRequestId id) const {
  const Request* r = find(id);
  return r ? r->status : PathStatus::Unknown;
}

const GridPath& PathService::path(PathRequestId id) const {
  const Request* r = find(id);
  return r && r->status == PathStatus::Ready ? r->path : empty_;
}

void PathService::setCell(Cell c, bool open) {
  if (!map_.inside(c.x, c.y) || map_.passable(c.x, c.y) == open) return;
  map_.setPassable(c.x, c.y, open);
  cellChanged(c, open);
}

void PathService::cellChanged(Cell c, bool open) {
  if (hpa_) hpa_->cellChanged(c);
  if (mesh_) rebuildMesh();
  if (open) {
    // Existing paths stay walkable; only cached answers might now be beaten, and requests
    // that had no path may now have one.
    cache_.clear();
    for (std::uint32_t slot = 0; slot < requests_.size(); ++slot) {
      Request& r = requests_[slot];
      if (r.status != PathStatus::NoPath) continue;
      r.status = PathStatus::Queued;
      queue_.push_back(PathRequestId{slot, r.generation});
      ++stats_.replans;
    }
    return;
  }
  if (config_.clear_cache_on_close)
    cache_.clear();
  else
    cache_.cellClosed(c);
  for (std::uint32_t slot = 0; slot < requests_.size(); ++slot) {
    Request& r = requests_[slot];
    if (r.status != PathStatus::Ready) continue;
    if (std::find(r.path.cells.begin(), r.path.cells.end(), c) == r.path.cells.end()) continue;
    r.status = PathStatus::Queued;
    r.path.clear();
    queue_.push_back(PathRequestId{slot, r.generation});
    ++stats_.replans;
  }
}

PathServiceStats PathService::stats() const {
  return stats_;
}

}  // namespace zonesim::ai
