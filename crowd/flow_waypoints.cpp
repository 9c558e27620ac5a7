#include "crowd/flow_waypoints.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "ai/funnel.h"
#include "ai/navmesh_search.h"
#include "crowd/flow_field.h"
#include "crowd/map_frame.h"

namespace zonesim::crowd {

namespace {

ai::Vec2 centreOf(int x, int y) {
  return ai::Vec2{x + 0.5, y + 0.5};
}

// The portal between polygons `from` and `into` as the funnel meets it; false when they share
// none (they touch at a corner only, or not at all).
bool portalBetween(const ai::NavMesh& mesh, std::int32_t from, std::int32_t into,
                   ai::FunnelPortal& out) {
  for (const std::int32_t* k = mesh.portalsBegin(from); k != mesh.portalsEnd(from); ++k) {
    const ai::NavPortal& p = mesh.portals()[std::size_t(*k)];
    if (p.other(from) == into) {
      out = ai::orientedPortal(p, into);
      return true;
    }
  }
  return false;
}

// Feeds `puller` the portals the grid field's path from `c` crosses (its cells' polygons in
// turn), then the goal, and stops at the first corner. A diagonal step between polygons that
// meet only at a corner crosses the polygon of one of the two cells beside it (the field never
// cuts a blocked corner, so both are open). False when the path leaves the mesh (a static box
// the grid field does not know).
bool headOf(const ai::NavMesh& mesh, const FlowField& field, ai::Cell c, ai::Vec2 goal,
            ai::StringPuller& puller) {
  std::int32_t at = mesh.polygonAt(c.x, c.y);
  ai::FunnelPortal portal;
  auto enter = [&](std::int32_t into) {
    if (into == at) return true;
    if (into < 0 || !portalBetween(mesh, at, into, portal)) return false;
    puller.add(portal);
    at = into;
    return true;
  };
  for (ai::Cell next; field.next(c, next); c = next) {
    const std::int32_t into = mesh.polygonAt(next.x, next.y);
    if (!enter(into)) {
      const std::int32_t side_x = mesh.polygonAt(next.x, c.y), side_y = mesh.polygonAt(c.x, next.y);
      if (!(enter(side_x) && enter(into)) && !(enter(side_y) && enter(into))) return false;
    }
    if (puller.corners().size() > 1) return true;  // the rest cannot move the first corner
  }
  puller.add({goal, goal});
  return true;
}

// A corner of the funnelled path lies on a lattice point at the end of a wall: of the four cells
// around it, the path bends round the one off the mesh. Moved `clearance` away from that cell
// along both axes, agents aiming at it pass the wall's end at that distance or more. A point
// with no such cell, or two (a pinch between diagonal walls), stays where it is.
ai::Vec2 clearOfWall(const ai::NavMesh& mesh, ai::Vec2 corner, double clearance) {
  const int cx = int(std::lround(corner.x)), cy = int(std::lround(corner.y));
  if (clearance <= 0 || corner.x != cx || corner.y != cy) return corner;
  int blocked = 0, bx = 0, by = 0;
  for (int dy = -1; dy <= 0; ++dy)
    for (int dx = -1; dx <= 0; ++dx)
      if (mesh.polygonAt(cx + dx, cy + dy) < 0) {
        ++blocked;
        bx = dx;
        by = dy;
      }
  if (blocked != 1) return corner;
  // The blocked cell is [cx+bx, cx+bx+1) x [cy+by, cy+by+1): away from it is +x when it lies
  // at dx = -1, -x when at dx = 0; the same for y.
  return ai::Vec2{corner.x + (bx < 0 ? clearance : -clearance),
                  corner.y + (by < 0 ? clearance : -clearance)};
}

}  // namespace

std::vector<float> navMeshWaypoints(const ai::NavMesh& mesh, const FlowField& field,
                                    double clearance, const ai::GridMap* walls) {
  const ai::Cell goal = field.goal();
  const int goal_polygon = mesh.polygonAt(goal.x, goal.y);
  if (goal_polygon < 0)
    throw std::invalid_argument("navmesh flow: goal cell (" + std::to_string(goal.x) + ", " +
                                std::to_string(goal.y) + ") is off the mesh");
  const ai::Vec2 to = centreOf(goal.x, goal.y);
  std::vector<float> aims(2 * std::size_t(mesh.width()) * std::size_t(mesh.height()),
                          std::numeric_limits<float>::quiet_NaN());
  auto set = [&](int x, int y, ai::Vec2 p) {
    const std::size_t at = 2 * (std::size_t(y) * std::size_t(mesh.width()) + std::size_t(x));
    aims[at] = float(p.x);
    aims[at + 1] = float(p.y);
  };
  for (int y = 0; y < mesh.height(); ++y)
    for (int x = 0; x < mesh.width(); ++x) {
      const int p = mesh.polygonAt(x, y);
      if (p < 0 || field.distance(ai::Cell{x, y}) < 0) continue;
      if (p == goal_polygon) {  // convex: the goal is in sight from every cell
        set(x, y, to);
        continue;
      }
      const ai::Vec2 from = centreOf(x, y);
      ai::StringPuller puller(from);
      if (!headOf(mesh, field, ai::Cell{x, y}, to, puller)) continue;
      if (puller.corners().size() < 2) {  // no corner before the goal
        set(x, y, to);
        continue;
      }
      const ai::Vec2 bend = puller.corners()[1];
      // A corner moved off one wall may have moved behind another: then the bend itself.
      const ai::Vec2 clear = clearOfWall(mesh, bend, clearance);
      const bool seen =
          !walls || lineOfSight(*walls, MapFrame{}, Vec2{from.x, from.y}, Vec2{clear.x, clear.y});
      set(x, y, seen ? clear : bend);
    }
  return aims;
}

}  // namespace zonesim::crowd
