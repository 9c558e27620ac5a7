#include "zone_node/systems/agent_navigation.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace zonesim::zone {

namespace {

std::int32_t navOf(AgentNav n) {
  return std::int32_t(n);
}

// Cell index pairs of an agent's path, from position `from` on.
bool pathCrosses(const AgentData& a, int x, int y) {
  for (std::size_t k = 0; k + 1 < a.path.size(); k += 2)
    if (a.path[k] == x && a.path[k + 1] == y) return true;
  return false;
}

}  // namespace

AgentNavigation::AgentNavigation(const Scene& scene, const ai::GridMap* grid,
                                 const crowd::MapFrame& frame)
    : scene_(scene), frame_(frame) {
  if (!grid) return;
  grid_ = *grid;
  for (const AgentDoor& d : scene.agents.doors)
    if (!grid_.inside(d.x, d.y))
      throw SceneError(d.file + ":" + std::to_string(d.line) + ": agents.doors: cell (" +
                       std::to_string(d.x) + ", " + std::to_string(d.y) + ") is off the " +
                       std::to_string(grid_.width()) + "x" + std::to_string(grid_.height()) +
                       " map");
  ai::PathServiceConfig c;
  const AgentPathSettings& p = scene.agents.paths;
  c.planner = p.hpa ? ai::PlannerKind::Hpa : ai::PlannerKind::AStar;
  c.hpa.clusterSize = p.cluster_size;
  c.pathsPerTick = p.paths_per_tick;
  c.expansionsPerTick = p.expansions_per_tick;
  c.cacheCapacity = std::size_t(p.cache);
  service_ = std::make_unique<ai::PathService>(grid_, c);
}

AgentNavigation::~AgentNavigation() = default;

void AgentNavigation::applyDoors(double time, EntityStore& store) {
  const std::vector<AgentDoor>& doors = scene_.agents.doors;
  while (next_door_ < doors.size() && doors[next_door_].at_s <= time + 1e-9) {
    const AgentDoor& d = doors[next_door_++];
    if (!service_ || !grid_.inside(d.x, d.y)) continue;
    service_->setCell(ai::Cell{d.x, d.y}, d.open);
    ++map_changes_;
    for (std::size_t i = 0; i < store.size(); ++i) {
      AgentData& a = store.agent[i];
      if (a.type < 0) continue;
      bool cut = !d.open && a.nav == navOf(AgentNav::Moving) && pathCrosses(a, d.x, d.y);
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
  if (grid_.passable(c.x, c.y)) return c;
  // Standing in a cell that closed (a door shut on the agent): start from the open neighbour
  // whose centre is nearest, so the path leads out of it.
  ai::Cell best = c;
  double best_d = 1e300;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ai::Cell n{c.x + dx, c.y + dy};
      if (!grid_.passable(n.x, n.y)) continue;
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

void AgentNavigation::want(EntityStore& store, std::size_t i, double x, double z, bool navigate) {
  AgentData& a = store.agent[i];
  bool moved_target = a.target_x != x || a.target_z != z;
  if (moved_target && a.nav != navOf(AgentNav::None)) {
    a.nav = navOf(AgentNav::None);
    a.path.clear();
  }
  // An agent that arrived here waiting for a path its old zone was planning asks again.
  if (a.nav == navOf(AgentNav::Waiting) && !pending_.count(store.id[i].value))
    a.nav = navOf(AgentNav::None);
  if (a.nav != navOf(AgentNav::None)) return;
  a.target_x = x;
  a.target_z = z;
  a.origin_x = store.pos[i].x();
  a.origin_z = store.pos[i].z();
  a.travelled = 0;
  if (!navigate || !service_) {
    a.nav = navOf(AgentNav::Moving);  // straight at the target
    return;
  }
  a.nav = navOf(AgentNav::Waiting);
  requests_.push_back({store.id[i], startCell(a.origin_x, a.origin_z), frame_.cellOf({x, z})});
}

void AgentNavigation::plan(EntityStore& store) {
  if (!service_) return;
  // Queued in id order, so the budget serves agents in an order no store layout changes.
  std::sort(requests_.begin(), requests_.end(),
            [](const Request& l, const Request& r) { return l.id < r.id; });
  for (const Request& r : requests_) pending_[r.id.value] = service_->request(r.from, r.to);
  requests_.clear();
  service_->tick();
  for (std::size_t i = 0; i < store.size(); ++i) {
    AgentData& a = store.agent[i];
    if (a.type < 0 || a.nav != navOf(AgentNav::Waiting)) continue;
    auto it = pending_.find(store.id[i].value);
    if (it == pending_.end()) continue;
    ai::PathStatus s = service_->status(it->second);
    if (s == ai::PathStatus::Queued) continue;
    if (s == ai::PathStatus::Ready) {
      const ai::GridPath& p = service_->path(it->second);
      a.path.clear();
      for (const ai::Cell& c : p.cells) {
        a.path.push_back(c.x);
        a.path.push_back(c.y);
      }
      a.nav = navOf(AgentNav::Moving);
    } else {
      a.nav = navOf(AgentNav::NoPath);
    }
    service_->release(it->second);
    pending_.erase(it);
  }
  // Requests of agents that left the zone while waiting: the new owner asks again.
  for (auto it = pending_.begin(); it != pending_.end();) {
    std::optional<std::size_t> i = store.indexOf(EntityId{it->first});
    if (i && store.agent[*i].nav == navOf(AgentNav::Waiting)) {
      ++it;
      continue;
    }
    service_->release(it->second);
    it = pending_.erase(it);
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
  // From the exact start through the inner cell centres to the exact target.
  std::vector<ai::Vec2> points{{a.origin_x, a.origin_z}};
  for (std::size_t k = 2; k + 2 < a.path.size(); k += 2) {
    crowd::Vec2 c = frame_.centre(ai::Cell{a.path[k], a.path[k + 1]});
    points.push_back({c.x, c.y});
  }
  points.push_back({a.target_x, a.target_z});
  s.spline = std::make_unique<ai::SplinePath>(std::move(points));
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

AgentPathStats AgentNavigation::takeStats() {
  AgentPathStats s;
  if (service_) {
    ai::PathServiceStats now = service_->stats();
    s.planned = now.planned - planned_before_;
    planned_before_ = now.planned;
    s.queued = service_->queued();
  }
  s.replans = replans_;
  replans_ = 0;
  return s;
}

}  // namespace zonesim::zone
