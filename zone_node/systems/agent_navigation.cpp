#include "zone_node/systems/agent_navigation.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>
#include <utility>

#include "ai/segment_cells.h"
#include "common/scene.h"
#include "zone_node/systems/navmesh_obstacles.h"

namespace zonesim::zone {

namespace {

std::int32_t navOf(AgentNav n) {
  return std::int32_t(n);
}

// Cell index pairs of an agent's grid path.
bool pathCrosses(const AgentData& a, int x, int y) {
  for (std::size_t k = 0; k + 1 < a.path.size(); k += 2)
    if (a.path[k] == x && a.path[k + 1] == y) return true;
  return false;
}

ai::PlannerKind plannerOf(AgentPlanner p) {
  switch (p) {
    case AgentPlanner::Hpa:
      return ai::PlannerKind::Hpa;
    case AgentPlanner::NavMesh:
      return ai::PlannerKind::NavMesh;
    case AgentPlanner::Jps:
      return ai::PlannerKind::Jps;
    case AgentPlanner::AStar:
      break;
  }
  return ai::PlannerKind::AStar;
}

}  // namespace

AgentNavigation::AgentNavigation(const Scene& scene, ZoneMap* map)
    : scene_(scene), map_(map), frame_(map ? map->world().frame : crowd::MapFrame{}) {
  if (!map) return;
  ai::PathServiceConfig c;
  const AgentPathSettings& p = scene.agents.paths;
  c.planner = plannerOf(p.planner);
  navmesh_ = p.planner == AgentPlanner::NavMesh;
  c.hpa.cluster_size = p.cluster_size;
  c.paths_per_tick = p.paths_per_tick;
  c.expansions_per_tick = p.expansions_per_tick;
  c.cache_capacity = std::size_t(p.cache);
  c.landmarks = p.landmarks;  // the loader's limit, 32, is LandmarkHeuristic's
  static_assert(ai::LandmarkHeuristic::kMaxLandmarks == 32);
  // Caches differ between ranks, so a hit must be exactly what a fresh plan would give: the
  // planners are deterministic for a given map (A* and HPA* break every tie by a fixed order),
  // and any door, closing or opening, clears the cache.
  c.clear_cache_on_close = true;
  c.audit = p.audit;
  // The mesh's clearance and obstacles (map.agent_radius, map.static_bodies): in cells.
  c.navmesh = navMeshConfig(scene, frame_);
  if (navmesh_) c.navmesh_boxes = navMeshBoxes(scene, frame_);
  service_ = std::make_unique<ai::PathService>(map->serviceGrid(), c);
}

AgentNavigation::~AgentNavigation() = default;

void AgentNavigation::followDoors(EntityStore& store) {
  if (!service_) return;
  for (const ZoneMap::DoorChange& change : map_->doorsNow()) {
    const MapDoor& d = *change.door;
    if (change.changed) service_->cellChanged(ai::Cell{d.x, d.y}, d.open);
    ++map_changes_;
    for (std::size_t i = 0; i < store.size(); ++i) {
      AgentData& a = store.agent[i];
      if (a.type < 0) continue;
      bool cut = !d.open && a.nav == navOf(AgentNav::Moving) &&
                 (navmesh_ ? meshPathTouches(a, ai::Cell{d.x, d.y}) : pathCrosses(a, d.x, d.y));
      bool retry = d.open && a.nav == navOf(AgentNav::NoPath);
      if (!cut && !retry) continue;
      a.nav = navOf(AgentNav::None);
      a.path.clear();
      ++a.replans;
      ++replans_;
    }
  }
}

ai::Cell AgentNavigation::startCell(double x, double z) const {
  ai::Cell c = frame_.cellOf({x, z});
  if (map_->world().grid.passable(c.x, c.y)) return c;
  // Standing in a cell that closed (a door shut on the agent): start from the open neighbour
  // whose centre is nearest, so the path leads out of it.
  ai::Cell best = c;
  double best_d = 1e300;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ai::Cell n{c.x + dx, c.y + dy};
      if (!map_->world().grid.passable(n.x, n.y)) continue;
      crowd::Vec2 m = frame_.centre(n);
      double d = std::hypot(m.x - x, m.y - z);
      if (d < best_d) {
        best_d = d;
        best = n;
      }
    }
  }
  return best;
}

ai::Vec2 AgentNavigation::meshStart(ai::Vec2 p) const {
  if (service_->onMesh(p)) return p;
  // Off the mesh but on open ground: within the agent radius of a wall, where an agent stops
  // that reached a goal on the mesh's edge within its arrival distance. Start from the nearest
  // cell centre the mesh covers, in the nearest ring of cells that has one (the band the
  // radius takes off is at most radius + 1 cells wide).
  const ai::Cell c{int(std::floor(p.x)), int(std::floor(p.y))};
  const int reach = int(std::ceil(scene_.map.agent_radius / frame_.cell_size)) + 1;
  for (int ring = 1; ring <= reach; ++ring) {
    ai::Vec2 best = p;
    double best_d = 1e300;
    for (int dy = -ring; dy <= ring; ++dy) {
      for (int dx = -ring; dx <= ring; ++dx) {
        if (std::max(std::abs(dx), std::abs(dy)) != ring) continue;
        const ai::Vec2 m{c.x + dx + 0.5, c.y + dy + 0.5};
        const double d = std::hypot(m.x - p.x, m.y - p.y);
        if (d < best_d && service_->onMesh(m)) {
          best_d = d;
          best = m;
        }
      }
    }
    if (best_d < 1e300) return best;
  }
  return p;  // nothing near: the plan fails, as for any start off the mesh
}

void AgentNavigation::want(EntityStore& store, std::size_t i, double x, double z, bool navigate,
                           std::int64_t tick) {
  AgentData& a = store.agent[i];
  bool moved_target = a.target_x != x || a.target_z != z;
  if (moved_target && a.nav != navOf(AgentNav::None)) {
    a.nav = navOf(AgentNav::None);
    a.path.clear();
  }
  if (a.nav != navOf(AgentNav::None)) return;  // a waiting request migrated with its agent
  a.target_x = x;
  a.target_z = z;
  a.origin_x = store.pos[i].x();
  a.origin_z = store.pos[i].z();
  a.travelled = 0;
  if (!navigate || !service_) {
    a.nav = navOf(AgentNav::Moving);  // straight at the target
    return;
  }
  // The request's age orders it in the cluster's queue; it migrates with the agent like the
  // rest of the request (origin and target).
  a.nav = navOf(AgentNav::Waiting);
  a.asked_tick = std::uint64_t(tick);
}

void AgentNavigation::plan(EntityStore& store, const ClusterGather& gather) {
  if (!service_) return;
  const std::size_t budget = std::size_t(scene_.agents.paths.paths_per_tick);
  const long expansion_budget = scene_.agents.paths.expansions_per_tick;
  waiting_.clear();
  for (std::size_t i = 0; i < store.size(); ++i) {
    const AgentData& a = store.agent[i];
    if (a.type < 0 || a.nav != navOf(AgentNav::Waiting)) continue;
    waiting_.push_back(Waiting{a.asked_tick, store.id[i].value, i, -1, false, {}});
  }
  auto byKey = [](const Waiting& l, const Waiting& r) {
    return l.asked != r.asked ? l.asked < r.asked : l.id < r.id;
  };
  std::sort(waiting_.begin(), waiting_.end(), byKey);
  // Only a zone's oldest `budget` requests can be among the cluster's oldest `budget`.
  std::vector<std::uint64_t> keys;
  for (std::size_t k = 0; k < waiting_.size() && k < budget; ++k) {
    keys.push_back(waiting_[k].asked);
    keys.push_back(waiting_[k].id);
  }
  std::vector<std::uint64_t> all = gather ? gather(keys) : keys;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> window;
  for (std::size_t k = 0; k + 1 < all.size(); k += 2) window.emplace_back(all[k], all[k + 1]);
  std::sort(window.begin(), window.end());
  if (window.size() > budget) window.resize(budget);
  // Plan this zone's requests of the window in the window's order. A zone stops once its own
  // plans expanded the budget: every later request of the window has at least that much
  // before it cluster-wide, so the cut below falls before it anyway.
  long mine_expanded = 0;
  std::size_t next = 0;  // waiting_ is in the window's order too
  for (const auto& key : window) {
    if (next >= waiting_.size() || waiting_[next].asked != key.first ||
        waiting_[next].id != key.second)
      continue;  // another zone's
    Waiting& w = waiting_[next++];
    if (expansion_budget > 0 && mine_expanded >= expansion_budget) continue;
    const AgentData& a = store.agent[w.index];
    ai::Cell to = frame_.cellOf({a.target_x, a.target_z});
    ai::Cell from = startCell(a.origin_x, a.origin_z);
    if (navmesh_) {
      // From the exact origin, or from the centre of the open cell next to it when a door
      // shut on the agent; to the exact target.
      ai::Vec2 start = toMap(a.origin_x, a.origin_z);
      if (!(frame_.cellOf({a.origin_x, a.origin_z}) == from)) start = {from.x + 0.5, from.y + 0.5};
      start = meshStart(start);
      w.found = service_->solveBetween(start, toMap(a.target_x, a.target_z), w.path, w.expanded);
    } else {
      w.found = service_->solve(from, to, w.path, w.expanded);
    }
    mine_expanded += w.expanded;
  }
  // How many requests of the window are served: all of them, or with an expansion budget those
  // before the first whose predecessors expanded it (the first is always served).
  std::size_t served = window.size();
  if (expansion_budget > 0 && !window.empty()) {
    std::vector<std::uint64_t> counts;
    for (std::size_t k = 0; k < next; ++k) {
      if (waiting_[k].expanded < 0) continue;
      counts.push_back(waiting_[k].id);
      counts.push_back(std::uint64_t(waiting_[k].expanded));
    }
    std::vector<std::uint64_t> gathered = gather ? gather(counts) : counts;
    std::unordered_map<std::uint64_t, std::uint64_t> expanded_by_id;
    for (std::size_t k = 0; k + 1 < gathered.size(); k += 2)
      expanded_by_id[gathered[k]] = gathered[k + 1];
    long before = 0;
    for (served = 0; served < window.size(); ++served) {
      auto it = expanded_by_id.find(window[served].second);
      if (before >= expansion_budget || it == expanded_by_id.end()) break;
      before += long(it->second);
    }
  }
  // Hand out the served paths; the rest keep waiting (a plan past the cut is dropped, though
  // the cache may keep it).
  std::size_t k = 0;
  for (std::size_t j = 0; j < served && k < next; ++j) {
    Waiting& w = waiting_[k];
    if (w.asked != window[j].first || w.id != window[j].second) continue;
    ++k;
    AgentData& a = store.agent[w.index];
    a.travelled = 0;
    a.path.clear();
    if (w.found && navmesh_) {
      // The end cells, and between them the mesh's corners: lattice points, so exact ints.
      const ai::Cell first = w.path.cells.front(), last = w.path.cells.back();
      a.path.insert(a.path.end(), {first.x, first.y});
      for (std::size_t p = 1; p + 1 < w.path.points.size(); ++p) {
        a.path.push_back(std::int32_t(std::lround(w.path.points[p].x)));
        a.path.push_back(std::int32_t(std::lround(w.path.points[p].y)));
      }
      a.path.insert(a.path.end(), {last.x, last.y});
      a.nav = navOf(AgentNav::Moving);
    } else if (w.found) {
      for (const ai::Cell& c : w.path.cells) {
        a.path.push_back(c.x);
        a.path.push_back(c.y);
      }
      a.nav = navOf(AgentNav::Moving);
    } else {
      a.nav = navOf(AgentNav::NoPath);
    }
    ++served_;
  }
  for (auto it = splines_.begin(); it != splines_.end();)
    it = store.indexOf(EntityId{it->first}) ? std::next(it) : splines_.erase(it);
}

const ai::SplinePath& AgentNavigation::splineOf(const EntityStore& store, std::size_t i) {
  const AgentData& a = store.agent[i];
  Spline& s = splines_[store.id[i].value];
  if (s.spline && s.path == a.path && s.ox == a.origin_x && s.oz == a.origin_z &&
      s.tx == a.target_x && s.tz == a.target_z)
    return *s.spline;
  s.path = a.path;
  s.ox = a.origin_x;
  s.oz = a.origin_z;
  s.tx = a.target_x;
  s.tz = a.target_z;
  // From the exact start through the inner cell centres (or mesh corners) to the exact target;
  // straight between mesh corners, which a curve would bulge past into the wall they bound.
  std::vector<ai::Vec2> points{{a.origin_x, a.origin_z}};
  for (std::size_t k = 2; k + 2 < a.path.size(); k += 2) {
    crowd::Vec2 c = navmesh_ ? cornerOf(a.path[k], a.path[k + 1])
                             : frame_.centre(ai::Cell{a.path[k], a.path[k + 1]});
    points.push_back({c.x, c.y});
  }
  points.push_back({a.target_x, a.target_z});
  s.spline = std::make_unique<ai::SplinePath>(
      std::move(points), 16,
      navmesh_ ? ai::SplinePath::Curve::Polyline : ai::SplinePath::Curve::CatmullRom);
  return *s.spline;
}

bool AgentNavigation::follow(EntityStore& store, std::size_t i, double speed, double accel,
                             double arrive, double dt, Vec3& desired) {
  AgentData& a = store.agent[i];
  desired = Vec3::Zero();
  if (a.nav != navOf(AgentNav::Moving)) return false;
  if (!a.path.empty()) {
    const ai::SplinePath& spline = splineOf(store, i);
    a.travelled = std::min(a.travelled + speed * dt, spline.length());
    ai::Vec2 p = spline.atDistance(a.travelled);
    Vec3 next(p.x, store.pos[i].y(), p.y);
    store.vel[i] = (next - store.pos[i]) / dt;
    store.pos[i] = next;
    if (a.travelled >= spline.length()) {
      a.nav = navOf(AgentNav::Arrived);
      a.path.clear();
      splines_.erase(store.id[i].value);
    }
    return true;
  }
  Vec3 to(a.target_x - store.pos[i].x(), 0, a.target_z - store.pos[i].z());
  double dist = to.norm();
  if (dist < arrive) {
    a.nav = navOf(AgentNav::Arrived);
    return false;
  }
  // Slow down inside the braking distance so agents arrive instead of orbiting the target.
  double brake = speed * speed / (2.0 * accel);
  desired = to * ((dist < brake ? speed * dist / brake : speed) / dist);
  return false;
}

crowd::Vec2 AgentNavigation::fleeTarget(double x, double z, double ex, double ez,
                                        double radius) const {
  const crowd::Vec2 from{x, z};
  crowd::Vec2 best = frame_.centre(startCell(x, z));
  double best_d = std::hypot(best.x - ex, best.y - ez);
  const double step = 0.5 * frame_.cell_size;
  const double kPi = 3.14159265358979323846;
  for (int k = 0; k < 16; ++k) {
    const double dx = std::cos(kPi * k / 8), dz = std::sin(kPi * k / 8);
    // March out along the ray while the point stays in plain view of the agent.
    for (double r = step; r <= radius + 1e-9; r += step) {
      crowd::Vec2 p{x + dx * r, z + dz * r};
      if (!crowd::walkable(map_->world().grid, frame_, p) ||
          !crowd::lineOfSight(map_->world().grid, frame_, from, p))
        break;
      crowd::Vec2 c = frame_.centre(frame_.cellOf(p));
      double d = std::hypot(c.x - ex, c.y - ez);
      if (d > best_d) {
        best_d = d;
        best = c;
      }
    }
  }
  return best;
}

ai::Vec2 AgentNavigation::toMap(double x, double z) const {
  return frame_.toMap(crowd::Vec2{x, z});
}

crowd::Vec2 AgentNavigation::cornerOf(std::int32_t x, std::int32_t y) const {
  return frame_.toWorld(x, y);
}

bool AgentNavigation::meshPathTouches(const AgentData& a, ai::Cell cell) const {
  // The walked polyline: exact origin, the corners, exact target.
  ai::Vec2 prev = toMap(a.origin_x, a.origin_z);
  for (std::size_t k = 2; k + 2 <= a.path.size(); k += 2) {
    const bool last = k + 2 == a.path.size();
    const ai::Vec2 next =
        last ? toMap(a.target_x, a.target_z) : ai::Vec2{double(a.path[k]), double(a.path[k + 1])};
    // Touching is enough: a segment along the edge of the door and a wall passes between them.
    if (ai::segmentMeetsCell(prev, next, cell, ai::CellContact::Closed)) return true;
    prev = next;
  }
  return false;
}

AgentPathStats AgentNavigation::takeStats() {
  AgentPathStats s;
  s.planned = served_;
  served_ = 0;
  s.queued = waiting_.size() - std::min(waiting_.size(), std::size_t(s.planned));
  s.replans = replans_;
  replans_ = 0;
  if (service_) {
    // The service counts from its start; the tick's share is what it added since the last call.
    const ai::PathServiceStats now = service_->stats();
    s.audited = now.audited - seen_.audited;
    s.overhead_ppm = std::uint64_t(std::llround((now.overhead_sum - seen_.overhead_sum) * 1e6));
    s.overhead_max_ppm = std::uint64_t(std::llround(now.overhead_max * 1e6));
    s.plan_ns = std::uint64_t(now.plan_ns - seen_.plan_ns);
    s.audit_ns = std::uint64_t(now.audit_ns - seen_.audit_ns);
    seen_ = now;
  }
  return s;
}

}  // namespace zonesim::zone
