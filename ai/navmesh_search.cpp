#include "ai/navmesh_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "ai/funnel.h"

namespace zonesim::ai {

namespace {

double distance(Vec2 a, Vec2 b) {
  return std::hypot(b.x - a.x, b.y - a.y);
}

// The point of portal p nearest to where the line from `from` to `goal` crosses the portal's
// line (clamped to the portal); the projection of `from` when the line runs parallel to it.
Vec2 crossingPoint(const NavPortal& p, Vec2 from, Vec2 goal) {
  const bool vertical = p.x0 == p.x1;
  const double across = vertical ? p.x0 : p.y0;
  const double lo = vertical ? p.y0 : p.x0, hi = vertical ? p.y1 : p.x1;
  const double fa = vertical ? from.x : from.y, fb = vertical ? from.y : from.x;
  const double ga = vertical ? goal.x : goal.y, gb = vertical ? goal.y : goal.x;
  double along = fb;
  if (ga != fa) along = fb + (gb - fb) * ((across - fa) / (ga - fa));
  along = std::clamp(along, lo, hi);
  return vertical ? Vec2{across, along} : Vec2{along, across};
}

[[noreturn]] void offMesh(const char* which, Vec2 p, const NavMesh& mesh) {
  std::ostringstream msg;
  msg << "navmesh: " << which << " (" << p.x << ", " << p.y << ") is off the mesh: ";
  if (!(p.x >= 0 && p.y >= 0 && p.x < mesh.width() && p.y < mesh.height()))
    msg << "outside the " << mesh.width() << " x " << mesh.height() << " map";
  else
    msg << "cell (" << int(std::floor(p.x)) << ", " << int(std::floor(p.y))
        << ") is blocked or within the agent radius (" << mesh.config().agent_radius
        << ") of a wall";
  throw std::invalid_argument(msg.str());
}

}  // namespace

FunnelPortal orientedPortal(const NavPortal& p, std::int32_t into) {
  const bool forward = into == p.high;  // travelling toward larger x (vertical) or y
  const Vec2 a{double(p.x0), double(p.y0)}, b{double(p.x1), double(p.y1)};
  if (p.x0 == p.x1) return forward ? FunnelPortal{b, a} : FunnelPortal{a, b};
  return forward ? FunnelPortal{a, b} : FunnelPortal{b, a};
}

NavMeshSearch::NavMeshSearch(const NavMesh& mesh)
    : mesh_(mesh), nodes_(mesh.portals().size() + 1) {}

bool NavMeshSearch::findPath(Cell from, Cell to, NavPath& out) {
  return findPath(Vec2{from.x + 0.5, from.y + 0.5}, Vec2{to.x + 0.5, to.y + 0.5}, out);
}

void NavMeshSearch::push(const Entry& e) {
  heap_.push_back(e);
  // Min-heap on f, then on the node index, so equal f pop in a fixed order.
  std::push_heap(heap_.begin(), heap_.end(), [](const Entry& a, const Entry& b) {
    return a.f != b.f ? a.f > b.f : a.node > b.node;
  });
}

NavMeshSearch::Entry NavMeshSearch::pop() {
  std::pop_heap(heap_.begin(), heap_.end(), [](const Entry& a, const Entry& b) {
    return a.f != b.f ? a.f > b.f : a.node > b.node;
  });
  Entry e = heap_.back();
  heap_.pop_back();
  return e;
}

void NavMeshSearch::relax(std::int32_t portal, std::int32_t parent, Vec2 from, double g,
                          std::int32_t into, Vec2 goal) {
  Node& n = nodes_[std::size_t(portal)];
  const Vec2 at = crossingPoint(mesh_.portals()[std::size_t(portal)], from, goal);
  const double ng = g + distance(from, at);
  if (n.stamp == generation_ + 1) return;  // closed
  if (n.stamp == generation_ && n.g <= ng) return;
  n.stamp = generation_;
  n.g = ng;
  n.at = at;
  n.parent = parent;
  n.into = into;
  push(Entry{ng + distance(at, goal), ng, portal});
}

bool NavMeshSearch::findPath(Vec2 from, Vec2 to, NavPath& out) {
  out.clear();
  expanded_ = 0;
  const int start_poly = mesh_.polygonAt(from), goal_poly = mesh_.polygonAt(to);
  if (start_poly < 0) offMesh("start", from, mesh_);
  if (goal_poly < 0) offMesh("goal", to, mesh_);
  std::vector<FunnelPortal> corridor;
  out.corridor.push_back(start_poly);
  if (start_poly != goal_poly) {
    generation_ += 2;
    heap_.clear();
    const auto goal_node = std::int32_t(mesh_.portals().size());
    for (const std::int32_t* e = mesh_.portalsBegin(start_poly); e != mesh_.portalsEnd(start_poly);
         ++e)
      relax(*e, -1, from, 0.0, mesh_.portals()[std::size_t(*e)].other(start_poly), to);
    Node& goal = nodes_[std::size_t(goal_node)];
    bool reached = false;
    while (!heap_.empty()) {
      const Entry e = pop();
      if (e.node == goal_node) {
        reached = true;
        break;
      }
      Node& n = nodes_[std::size_t(e.node)];
      if (n.stamp != generation_ || n.g != e.g) continue;  // closed, or a stale entry
      n.stamp = generation_ + 1;
      ++expanded_;
      if (n.into == goal_poly) {
        const double g = n.g + distance(n.at, to);
        if (goal.stamp != generation_ || g < goal.g) {
          goal.stamp = generation_;
          goal.g = g;
          goal.parent = e.node;
          push(Entry{g, g, goal_node});
        }
        continue;
      }
      for (const std::int32_t* p = mesh_.portalsBegin(n.into); p != mesh_.portalsEnd(n.into); ++p)
        if (*p != e.node)
          relax(*p, e.node, n.at, n.g, mesh_.portals()[std::size_t(*p)].other(n.into), to);
    }
    if (!reached) {
      out.clear();
      return false;
    }
    trail_.clear();
    for (std::int32_t k = goal.parent; k >= 0; k = nodes_[std::size_t(k)].parent)
      trail_.push_back(k);
    std::reverse(trail_.begin(), trail_.end());
    for (std::int32_t k : trail_) {
      const Node& n = nodes_[std::size_t(k)];
      corridor.push_back(orientedPortal(mesh_.portals()[std::size_t(k)], n.into));
      out.corridor.push_back(n.into);
    }
  }
  out.points = pullString(from, corridor, to);
  for (std::size_t k = 1; k < out.points.size(); ++k)
    out.length += distance(out.points[k - 1], out.points[k]);
  return true;
}

}  // namespace zonesim::ai
