#include "crowd/flow_crowd.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "crowd/flow_waypoints.h"

namespace zonesim::crowd {

FlowCrowd::FlowCrowd(const ai::GridMap& map, const MapFrame& frame,
                     const FlowCrowdSettings& settings)
    : map_(map), frame_(frame), settings_(settings) {
  if (!(settings.body_radius >= 0.0))
    throw std::invalid_argument("FlowCrowd: body_radius must be at least 0");
  if (settings.body_radius > 0.0 && !(settings.sight > 2.0 * settings.body_radius))
    throw std::invalid_argument("FlowCrowd: sight must exceed twice body_radius");
}

int FlowCrowd::addDestination(ai::Cell goal) {
  auto field = std::make_unique<FlowField>(map_, goal);
  aimOnMesh(*field);
  fields_.push_back(std::move(field));
  return int(fields_.size()) - 1;
}

int FlowCrowd::addDestination(std::unique_ptr<FlowField> field) {
  aimOnMesh(*field);
  fields_.push_back(std::move(field));
  return int(fields_.size()) - 1;
}

void FlowCrowd::aimOnMesh(FlowField& field) {
  if (!settings_.navmesh) return;
  if (!mesh_ || mesh_version_ != map_.version()) {
    // Not eroded: the clearance moves the corners instead (crowd/flow_waypoints.h).
    mesh_ = std::make_unique<ai::NavMesh>(map_, settings_.navmesh_boxes, ai::NavMeshConfig{});
    mesh_walls_ = std::make_unique<ai::GridMap>(map_);
    ai::closeBoxes(*mesh_walls_, settings_.navmesh_boxes);
    mesh_version_ = map_.version();
  }
  field.setWaypoints(
      navMeshWaypoints(*mesh_, field, settings_.navmesh_config.agent_radius, mesh_walls_.get()));
}

int FlowCrowd::refreshFields() {
  int rebuilt = 0;
  for (auto& f : fields_)
    if (f->mapVersion() != map_.version()) {
      f = std::make_unique<FlowField>(map_, f->goal());
      aimOnMesh(*f);
      ++rebuilt;
    }
  return rebuilt;
}

bool FlowCrowd::leaveClosedCell(const FlowField& f, ai::Cell c, ai::Cell& next) const {
  // A cell that closed under the agent (a door) has no direction: step to the open neighbour
  // from which the goal is nearest (fixed order on ties, so every rank picks the same).
  double best = -1;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      ai::Cell n{c.x + dx, c.y + dy};
      if ((dx == 0 && dy == 0) || !map_.passable(n.x, n.y)) continue;
      double d = f.distance(n);
      if (d < 0) continue;
      d += (dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0;
      if (best < 0 || d < best) {
        best = d;
        next = n;
      }
    }
  }
  return best >= 0;
}

Vec2 FlowCrowd::desiredVelocity(Vec2 pos, int d) const {
  ai::Cell c;
  return desiredVelocityAt(pos, d, c);
}

// Inlined into the step: called out of line, the position passed as two doubles was read back
// as one 16-byte vector that the stores could not forward (a stall of about 14% of this
// function in the 100k-agent profile, 5 December).
[[gnu::always_inline]] inline Vec2 FlowCrowd::desiredVelocityAt(Vec2 pos, int d,
                                                                ai::Cell& c) const {
  const FlowField& f = *fields_[d];
  c = frame_.cellOf(pos);
  ai::Cell next;
  Vec2 goal = frame_.centre(f.goal());
  if (c == f.goal()) {
    // Arrive: speed proportional to the remaining distance inside the slow radius.
    Vec2 to = goal - pos;
    double dist = length(to);
    double speed = settings_.max_speed * std::min(1.0, dist / settings_.slow_radius);
    return withLength(to, speed);
  }
  const bool onField = f.next(c, next);
  if (!onField && !(!map_.passable(c.x, c.y) && leaveClosedCell(f, c, next))) return {};
  Vec2 aim = frame_.centre(next);
  double ax, ay;
  if (f.hasWaypoints() && f.waypoint(c, ax, ay))  // on the mesh: the path's first corner
    aim = frame_.toWorld(ax, ay);
  Vec2 to = aim - pos;
  double speed = settings_.max_speed;
  // Most agents are far from their goal: where even the lower bound of the distance is past
  // the slow radius the slow-down cannot apply (a product of larger doubles is no smaller),
  // and the distance, a cache miss per agent, is not read.
  if (onField && f.nextCellLowerBound(c) * frame_.cell_size >= settings_.slow_radius)
    return withLength(to, speed);
  double remaining = f.distance(c) * frame_.cell_size;
  if (remaining < settings_.slow_radius) speed *= std::max(0.25, remaining / settings_.slow_radius);
  return withLength(to, speed);
}

bool FlowCrowd::hasArrived(Vec2 pos, int d) const {
  Vec2 goal = frame_.centre(fields_[d]->goal());
  return lengthSq(pos - goal) <= settings_.arrive_radius * settings_.arrive_radius;
}

Vec2 FlowCrowd::separation(std::int32_t self, KeepApart* gaps) const {
  // Reads the grid's coordinate arrays (16 bytes a candidate instead of a 48-byte entry) and
  // knows itself by its entry index (ids are unique); the sum is the same, in the same order.
  // The neighbours whose gaps bind are gathered in the same pass: a wider query visits more
  // entries but keeps the order of those within the separation radius.
  const double r = settings_.separation_radius, r2 = r * r;
  const double q = gaps ? std::max(r, gaps->queryRadius()) : r, q2 = q * q;
  const std::span<const GridEntry> entries = grid_.entries();
  const double* xs = grid_.xs();
  const double* ys = grid_.ys();
  const Vec2 p = entries[self].pos;
  Vec2 sep;
  grid_.forEachRowInBox(p, q, [&](std::int32_t begin, std::int32_t end) {
    for (std::int32_t k = begin; k < end; ++k) {
      if (k == self) continue;
      const Vec2 rel{xs[k] - p.x, ys[k] - p.y};
      const double d2 = lengthSq(rel);
      if (gaps && d2 < q2) gaps->neighbour(rel, entries[self].id < entries[k].id);
      if (d2 >= r2) continue;
      if (d2 > 1e-18) {
        const double d = std::sqrt(d2);
        sep += rel * (-(r / d - 1.0) / d);
      } else {
        sep.x += entries[self].id < entries[k].id ? -1e3 : 1e3;
      }
    }
  });
  return sep * settings_.separation_weight;
}

Vec2 FlowCrowd::keepGaps(Vec2 from, Vec2 to, double h, Vec2& vel) const {
  const Vec2 wish = to - from;
  const Vec2 x = keep_apart_.move(wish);
  if (x == wish) return to;
  // Kept short of a neighbour: the agent moves (and goes on) as it can. The new move may meet
  // a wall the first did not, so it slides again; a slide that breaks a gap stays put.
  vel = x * (1.0 / h);
  const Vec2 at = slideMove(map_, frame_, from, from + x, vel);
  if (keep_apart_.keeps(at - from)) return at;
  vel = Vec2{};
  return from;
}

void FlowCrowd::step(const AgentSpan& agents, std::span<const std::uint16_t> dest,
                     std::span<std::uint8_t> arrived, const GhostSpan& ghosts, double dt,
                     const StepPlan& plan) {
  const std::size_t n = agents.size();
  if (agents.pos.size() != n || agents.vel.size() != n || dest.size() != n || arrived.size() != n ||
      ghosts.pos.size() != ghosts.size() || ghosts.vel.size() != ghosts.size() ||
      (!plan.empty() && (plan.dt.size() != n || plan.steer.size() != n)))
    throw std::invalid_argument("FlowCrowd::step: array sizes differ");
  for (std::uint16_t d : dest)
    if (d >= fields_.size()) throw std::out_of_range("FlowCrowd::step: unknown destination");
  // Arrived agents have left the crowd: they are neither moved nor seen.
  grid_.build(agents.ids, agents.pos, agents.vel, ghosts,
              std::max(settings_.grid_cell, settings_.separation_radius), arrived,
              NeighbourGrid::Columns::kPositions);
  const std::span<const GridEntry> entries = grid_.entries();
  // Each agent reads its field's direction at its cell, a cache miss per line: the step
  // evicts the fields between one step and the next (about 17 MB touched at 100k agents), and
  // goes through them in an order that the hardware does not foresee (fetching a band of rows
  // ahead, or a line ahead per agent, did not help). Where the fields hold no more lines than
  // there are agents, loading them all at once first is cheaper (100k agents, 4 fields of
  // 256 KiB: 0.91 to 0.96 of the whole run in alternated runs, 5 December).
  std::size_t lines = 0;
  for (const auto& f : fields_) lines += f->directionLines();
  if (lines <= entries.size())
    for (const auto& f : fields_) f->prefetchDirections();
  // Velocity relaxes toward the desired one by the exact factor 1 - exp(-rate h), not rate h:
  // LOD steps of several ticks would overshoot (and beyond rate h = 2 diverge). Without a plan
  // every agent has the same h: one exp per step.
  const auto relaxFactor = [this](double h) { return 1.0 - std::exp(-settings_.steer_rate * h); };
  const double relaxDt = relaxFactor(dt);
  constexpr std::size_t kAhead = 8;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    // Agents come in cell order but are stored in the caller's order: fetch the lines of the
    // agents a few entries ahead (each is a cache miss in random storage order).
    if (k + kAhead < entries.size() && entries[k + kAhead].src >= 0) {
      const std::size_t a = static_cast<std::size_t>(entries[k + kAhead].src);
      __builtin_prefetch(&dest[a]);
      __builtin_prefetch(&arrived[a], 1);
      __builtin_prefetch(&agents.pos[a], 1);
      __builtin_prefetch(&agents.vel[a], 1);
      if (!plan.empty()) __builtin_prefetch(&plan.dt[a]);
    }
    const GridEntry& e = entries[k];
    if (e.src < 0) continue;
    const double h = plan.empty() ? dt : plan.dt[e.src];
    if (h <= 0.0) continue;
    const int d = dest[e.src];
    ai::Cell cell;
    Vec2 desired = desiredVelocityAt(e.pos, d, cell);
    Vec2 v;
    KeepApart* gaps = nullptr;  // kept apart: the neighbours that may bind this agent
    if (plan.empty() || plan.steer[e.src]) {
      if (settings_.body_radius > 0.0) {
        const double reach =
            std::min(settings_.max_speed * h, 0.5 * settings_.sight - settings_.body_radius);
        keep_apart_.begin(settings_.body_radius, reach);
        gaps = &keep_apart_;
      }
      const double relax = plan.empty() ? relaxDt : relaxFactor(h);
      Vec2 dv = (desired - e.vel) * relax + separation(std::int32_t(k), gaps) * h;
      v = clampLength(e.vel + clampLength(dv, settings_.max_force * h), settings_.max_speed);
    } else {
      v = desired;  // cheap update: ride the field, no neighbours, no inertia
    }
    Vec2 p = e.pos + v * h;
    // Most moves are short and stay in the agent's cell, where slideMove returns the target
    // as it is: decide that here with the cell already known (the same test slideMove makes
    // first), and leave every other move to it.
    const double half = 0.5 * frame_.cell_size;
    if (!(lengthSq(p - e.pos) < half * half * (1.0 - 1e-9) && frame_.cellOf(p) == cell))
      p = slideMove(map_, frame_, e.pos, p, v);
    if (gaps) p = keepGaps(e.pos, p, h, v);
    agents.pos[e.src] = p;
    agents.vel[e.src] = v;
    if (hasArrived(p, d)) {
      arrived[e.src] = 1;
      agents.vel[e.src] = Vec2{};
    }
  }
}

}  // namespace zonesim::crowd
