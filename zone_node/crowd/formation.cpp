#include "zone_node/crowd/formation.h"

#include <algorithm>
#include <stdexcept>

namespace zonesim::crowd {

Formation::Formation(const ai::GridMap& map, const MapFrame& frame,
                     const FormationSettings& settings, std::vector<Vec2> slotOffsets, Vec2 centre)
    : map_(map),
      frame_(frame),
      settings_(settings),
      slots_(std::move(slotOffsets)),
      members_(slots_.size()),
      search_(map),
      centre_(centre) {
  if (!walkable(map, frame, centre))
    throw std::invalid_argument("Formation: the centre is not on a walkable cell");
}

bool Formation::setDestination(Vec2 goal) {
  if (!walkable(map_, frame_, goal)) return false;
  if (!search_.findPath(frame_.cellOf(centre_), frame_.cellOf(goal), scratch_)) return false;
  route_.clear();
  route_.push_back(centre_);
  // Interior cell centres; the ends are the exact start and goal points. Segments between
  // consecutive points stay on the path's cells (A* never cuts a blocked corner).
  for (std::size_t k = 1; k + 1 < scratch_.cells.size(); ++k)
    route_.push_back(frame_.centre(scratch_.cells[k]));
  route_.push_back(goal);
  routeAt_ = 1;
  routeDone_ = false;
  return true;
}

Vec2 Formation::slotPosition(int i) const {
  Vec2 left{-heading_.y, heading_.x};
  return centre_ + heading_ * slots_[i].x + left * slots_[i].y;
}

void Formation::moveCentre(double dt) {
  Vec2 before = centre_;
  if (!routeDone_) {
    double remaining = length(route_[routeAt_] - centre_);
    for (std::size_t k = routeAt_ + 1; k < route_.size(); ++k)
      remaining += length(route_[k] - route_[k - 1]);
    // Slow down into the destination (so the members' pull fades, seed step 5), but not to a
    // crawl that never ends.
    double speed = settings_.centreSpeed * std::clamp(remaining / settings_.slowRadius, 0.2, 1.0);
    double s = speed * dt;
    while (s > 0 && !routeDone_) {
      Vec2 to = route_[routeAt_] - centre_;
      double d = length(to);
      if (d > s) {
        centre_ += to * (s / d);
        s = 0;
      } else {
        centre_ = route_[routeAt_];
        s -= d;
        if (++routeAt_ == route_.size()) {
          routeDone_ = true;
          routeAt_ = route_.size() - 1;
        }
      }
    }
  }
  centreVel_ = (centre_ - before) * (1.0 / dt);
  if (lengthSq(centreVel_) > 1e-12) {
    Vec2 target = withLength(centreVel_, 1.0);
    Vec2 h = heading_ + (target - heading_) * std::min(1.0, settings_.turnRate * dt);
    heading_ = lengthSq(h) > 1e-12 ? withLength(h, 1.0) : target;
  }
}

bool Formation::planRejoin(int i, Vec2 pos) {
  Member& m = members_[i];
  m.path.clear();
  m.at = 0;
  m.plannedFor = centre_;
  ++rejoinPlans_;
  if (!search_.findPath(frame_.cellOf(pos), frame_.cellOf(centre_), scratch_)) return false;
  for (std::size_t k = 1; k < scratch_.cells.size(); ++k)
    m.path.push_back(frame_.centre(scratch_.cells[k]));
  return true;
}

void Formation::updateMode(int i, Vec2 pos) {
  Member& m = members_[i];
  Vec2 slot = slotPosition(i);
  double slotDist = length(slot - pos);
  if (m.mode == MemberMode::InFormation) {
    if (!lineOfSight(map_, frame_, pos, centre_) || slotDist > settings_.cutOffDistance) {
      m.mode = MemberMode::Rejoining;
      planRejoin(i, pos);
    }
    return;
  }
  if (slotDist < settings_.rejoinDistance && walkable(map_, frame_, slot) &&
      lineOfSight(map_, frame_, pos, slot)) {
    m.mode = MemberMode::InFormation;
    m.path.clear();
    return;
  }
  if (length(centre_ - m.plannedFor) > settings_.replanDistance || m.at >= m.path.size())
    planRejoin(i, pos);
}

Vec2 Formation::desiredVelocity(int i, Vec2 pos) {
  Member& m = members_[i];
  Vec2 slot = slotPosition(i);
  auto towardSlot = [&] {
    return clampLength(centreVel_ + (slot - pos) * settings_.slotGain, settings_.memberMaxSpeed);
  };
  if (m.mode == MemberMode::InFormation) return towardSlot();
  if (walkable(map_, frame_, slot) && lineOfSight(map_, frame_, pos, slot)) return towardSlot();
  // Follow the rejoin path: drop reached waypoints, and skip ahead to ones in plain view.
  while (m.at < m.path.size() && length(m.path[m.at] - pos) < settings_.waypointRadius) ++m.at;
  for (int look = 0; look < 3 && m.at + 1 < m.path.size(); ++look) {
    if (!lineOfSight(map_, frame_, pos, m.path[m.at + 1])) break;
    ++m.at;
  }
  Vec2 target = m.at < m.path.size() ? m.path[m.at] : centre_;
  return withLength(target - pos, settings_.memberMaxSpeed);
}

Vec2 Formation::separation(int i, std::span<const Vec2> pos) const {
  const double r = settings_.separationRadius;
  Vec2 sep;
  for (std::size_t j = 0; j < pos.size(); ++j) {
    if (int(j) == i) continue;
    Vec2 rel = pos[j] - pos[i];
    double d2 = lengthSq(rel);
    if (d2 >= r * r) continue;
    if (d2 > 1e-18) {
      double d = std::sqrt(d2);
      sep += rel * (-(r / d - 1.0) / d);
    } else {
      sep.x += i < int(j) ? -1e3 : 1e3;
    }
  }
  return sep * settings_.separationWeight;
}

void Formation::step(std::span<Vec2> pos, std::span<Vec2> vel, double dt) {
  if (pos.size() != slots_.size() || vel.size() != slots_.size())
    throw std::invalid_argument("Formation::step: one position and velocity per slot");
  moveCentre(dt);
  snapshot_.assign(pos.begin(), pos.end());
  for (int i = 0; i < size(); ++i) {
    Vec2 p = snapshot_[i];
    updateMode(i, p);
    Vec2 desired = desiredVelocity(i, p);
    Vec2 acc = (desired - vel[i]) * settings_.steerRate + separation(i, snapshot_);
    Vec2 v =
        clampLength(vel[i] + clampLength(acc, settings_.maxForce) * dt, settings_.memberMaxSpeed);
    pos[i] = slideMove(map_, frame_, p, p + v * dt, v);
    vel[i] = v;
  }
}

}  // namespace zonesim::crowd
