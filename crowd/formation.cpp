#include "crowd/formation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ai/navmesh_search.h"

namespace zonesim::crowd {

bool planRoute(ai::GridSearch& search, const MapFrame& frame, std::span<const Vec2> points,
               std::vector<Vec2>& route) {
  route.clear();
  if (points.empty()) return true;
  route.push_back(points[0]);
  ai::GridPath leg;
  for (std::size_t p = 1; p < points.size(); ++p) {
    if (!search.findPath(frame.cellOf(points[p - 1]), frame.cellOf(points[p]), leg)) return false;
    // Interior cell centres; the ends are the exact points. Segments between consecutive
    // points stay on the path's cells (A* never cuts a blocked corner).
    for (std::size_t k = 1; k + 1 < leg.cells.size(); ++k)
      route.push_back(frame.centre(leg.cells[k]));
    route.push_back(points[p]);
  }
  return true;
}

bool planMeshRoute(ai::NavMeshSearch& search, const MapFrame& frame, std::span<const Vec2> points,
                   std::vector<Vec2>& route) {
  route.clear();
  if (points.empty()) return true;
  route.push_back(points[0]);
  ai::NavPath leg;
  for (std::size_t p = 1; p < points.size(); ++p) {
    if (!search.findPath(frame.toMap(points[p - 1]), frame.toMap(points[p]), leg)) return false;
    // The corners between; the ends are the exact points.
    for (std::size_t k = 1; k + 1 < leg.points.size(); ++k)
      route.push_back(frame.toWorld(leg.points[k].x, leg.points[k].y));
    route.push_back(points[p]);
  }
  return true;
}

FormationCentre::FormationCentre(const FormationSettings& settings, Vec2 at, Vec2 heading)
    : settings_(settings), at_(at), heading_(heading) {}

void FormationCentre::setRoute(std::vector<Vec2> route) {
  route_ = std::move(route);
  next_ = 1;
  done_ = route_.size() < 2;
}

Vec2 FormationCentre::slotPosition(Vec2 offset) const {
  Vec2 left{-heading_.y, heading_.x};
  return at_ + heading_ * offset.x + left * offset.y;
}

void FormationCentre::advance(double dt) {
  Vec2 before = at_;
  if (!done_) {
    double remaining = length(route_[next_] - at_);
    for (std::size_t k = next_ + 1; k < route_.size(); ++k)
      remaining += length(route_[k] - route_[k - 1]);
    // Slow down into the destination (so the members' pull fades, seed step 5), but not to a
    // crawl that never ends.
    double speed = settings_.centre_speed * std::clamp(remaining / settings_.slow_radius, 0.2, 1.0);
    double s = speed * dt;
    while (s > 0 && !done_) {
      Vec2 to = route_[next_] - at_;
      double d = length(to);
      if (d > s) {
        at_ += to * (s / d);
        s = 0;
      } else {
        at_ = route_[next_];
        s -= d;
        if (++next_ == route_.size()) {
          done_ = true;
          next_ = route_.size() - 1;
        }
      }
    }
  }
  vel_ = (at_ - before) * (1.0 / dt);
  if (lengthSq(vel_) > 1e-12) {
    Vec2 target = withLength(vel_, 1.0);
    Vec2 h = heading_ + (target - heading_) * std::min(1.0, settings_.turn_rate * dt);
    heading_ = lengthSq(h) > 1e-12 ? withLength(h, 1.0) : target;
  }
}

MemberStepper::MemberStepper(const ai::GridMap& map, const MapFrame& frame,
                             const FormationSettings& settings)
    : map_(map), frame_(frame), settings_(settings), search_(map) {}

Vec2 MemberStepper::waypoint(const MemberState& m, std::int32_t k) const {
  return frame_.centre(ai::Cell{m.path[std::size_t(2 * k)], m.path[std::size_t(2 * k + 1)]});
}

bool MemberStepper::planRejoin(MemberState& m, Vec2 pos, const FormationCentre& centre) {
  m.path.clear();
  m.at = 0;
  m.planned_for = centre.position();
  ++rejoin_plans_;
  if (!search_.findPath(frame_.cellOf(pos), frame_.cellOf(centre.position()), scratch_))
    return false;
  for (std::size_t k = 1; k < scratch_.cells.size(); ++k) {
    m.path.push_back(scratch_.cells[k].x);
    m.path.push_back(scratch_.cells[k].y);
  }
  return true;
}

void MemberStepper::updateMode(MemberState& m, Vec2 pos, Vec2 slot, const FormationCentre& centre) {
  double slotDist = length(slot - pos);
  if (m.mode == MemberMode::InFormation) {
    if (!lineOfSight(map_, frame_, pos, centre.position()) ||
        slotDist > settings_.cut_off_distance) {
      m.mode = MemberMode::Rejoining;
      planRejoin(m, pos, centre);
    }
    return;
  }
  if (slotDist < settings_.rejoin_distance && walkable(map_, frame_, slot) &&
      lineOfSight(map_, frame_, pos, slot)) {
    m.mode = MemberMode::InFormation;
    m.path.clear();
    m.at = 0;
    return;
  }
  const std::int32_t cells = std::int32_t(m.path.size() / 2);
  if (length(centre.position() - m.planned_for) > settings_.replan_distance || m.at >= cells)
    planRejoin(m, pos, centre);
}

Vec2 MemberStepper::desiredVelocity(MemberState& m, Vec2 pos, Vec2 slot,
                                    const FormationCentre& centre) const {
  auto towardSlot = [&] {
    return clampLength(centre.velocity() + (slot - pos) * settings_.slot_gain,
                       settings_.member_max_speed);
  };
  if (m.mode == MemberMode::InFormation) return towardSlot();
  if (walkable(map_, frame_, slot) && lineOfSight(map_, frame_, pos, slot)) return towardSlot();
  // Follow the rejoin path: drop reached waypoints, and skip ahead to ones in plain view.
  const std::int32_t cells = std::int32_t(m.path.size() / 2);
  while (m.at < cells && length(waypoint(m, m.at) - pos) < settings_.waypoint_radius) ++m.at;
  for (int look = 0; look < 3 && m.at + 1 < cells; ++look) {
    if (!lineOfSight(map_, frame_, pos, waypoint(m, m.at + 1))) break;
    ++m.at;
  }
  Vec2 target = m.at < cells ? waypoint(m, m.at) : centre.position();
  return withLength(target - pos, settings_.member_max_speed);
}

Vec2 MemberStepper::separation(std::uint64_t id, Vec2 pos,
                               std::span<const MemberNeighbour> others) const {
  const double r = settings_.separation_radius;
  Vec2 sep;
  for (const MemberNeighbour& o : others) {
    if (o.id == id) continue;
    Vec2 rel = o.pos - pos;
    double d2 = lengthSq(rel);
    if (d2 >= r * r) continue;
    if (d2 > 1e-18) {
      double d = std::sqrt(d2);
      sep += rel * (-(r / d - 1.0) / d);
    } else {
      sep.x += id < o.id ? -1e3 : 1e3;  // on top of each other: the ids decide who goes where
    }
  }
  return sep * settings_.separation_weight;
}

void MemberStepper::step(std::uint64_t id, MemberState& m, Vec2 offset,
                         const FormationCentre& centre, std::span<const MemberNeighbour> neighbours,
                         Vec2& pos, Vec2& vel, double dt) {
  const Vec2 p = pos;
  const Vec2 slot = centre.slotPosition(offset);
  updateMode(m, p, slot, centre);
  Vec2 desired = desiredVelocity(m, p, slot, centre);
  Vec2 acc = (desired - vel) * settings_.steer_rate + separation(id, p, neighbours);
  Vec2 v =
      clampLength(vel + clampLength(acc, settings_.max_force) * dt, settings_.member_max_speed);
  pos = slideMove(map_, frame_, p, p + v * dt, v);
  vel = v;
}

Formation::Formation(const ai::GridMap& map, const MapFrame& frame,
                     const FormationSettings& settings, std::vector<Vec2> slotOffsets, Vec2 centre)
    : map_(map),
      frame_(frame),
      slots_(std::move(slotOffsets)),
      members_(slots_.size()),
      centre_(settings, centre),
      stepper_(map, frame, settings),
      search_(map) {
  if (!walkable(map, frame, centre))
    throw std::invalid_argument("Formation: the centre is not on a walkable cell");
}

bool Formation::setDestination(Vec2 goal) {
  if (!walkable(map_, frame_, goal)) return false;
  const Vec2 points[2] = {centre_.position(), goal};
  std::vector<Vec2> route;
  if (!planRoute(search_, frame_, points, route)) return false;
  centre_.setRoute(std::move(route));
  return true;
}

void Formation::step(std::span<Vec2> pos, std::span<Vec2> vel, double dt) {
  if (pos.size() != slots_.size() || vel.size() != slots_.size())
    throw std::invalid_argument("Formation::step: one position and velocity per slot");
  centre_.advance(dt);
  snapshot_.clear();
  for (int i = 0; i < size(); ++i) snapshot_.push_back({std::uint64_t(i), pos[i]});
  for (int i = 0; i < size(); ++i)
    stepper_.step(std::uint64_t(i), members_[i], slots_[i], centre_, snapshot_, pos[i], vel[i], dt);
}

}  // namespace zonesim::crowd
