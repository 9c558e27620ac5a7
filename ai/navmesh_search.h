#pragma once
// Paths over a NavMesh: A* over the portals, then the funnel through the chosen corridor.
// A node is a portal, placed at the point of the portal nearest to the line from its parent's
// point to the goal (clamped to the portal), so a node's g is the length of a real polyline
// through the corridor and the straight-line heuristic to the goal is admissible for it; the
// search is not exact over all corridors (a node's point depends on its parent), which is
// why the length can exceed the corridor-optimal one (docs/ai.md reports by how much). Ties
// on f break by the lower portal index, so a query always gives the same path.

#include <cstdint>
#include <vector>

#include "ai/funnel.h"
#include "ai/navmesh.h"
#include "ai/octile.h"
#include "ai/vec2.h"

namespace zonesim::ai {

/// A path over the mesh: straight segments between corner points.
struct NavPath {
  std::vector<Vec2> points;            ///< start first, goal last (one point when equal)
  double length = 0.0;                 ///< sum of the segments' lengths
  std::vector<std::int32_t> corridor;  ///< polygons crossed, start's first
  /// Empties the path, keeping its capacity.
  void clear() {
    points.clear();
    corridor.clear();
    length = 0.0;
  }
};

/// The portal's ends as a traveller entering polygon `into` meets them (the funnel's left and
/// right).
FunnelPortal orientedPortal(const NavPortal& p, std::int32_t into);

/// Reusable searcher over one mesh (which must outlive it).
class NavMeshSearch {
 public:
  /// Sizes the node records for `mesh`.
  explicit NavMeshSearch(const NavMesh& mesh);

  /// Shortest corridor path from point `from` to point `to` (map units); false (and `out`
  /// empty) when they are not connected. Throws std::invalid_argument naming the point when
  /// either is off the mesh (outside the map, blocked, or within the agent radius of a wall).
  bool findPath(Vec2 from, Vec2 to, NavPath& out);
  /// As above between the centres of two cells.
  bool findPath(Cell from, Cell to, NavPath& out);
  /// Portals expanded by the last search.
  int lastExpanded() const { return expanded_; }
  /// The mesh searched.
  const NavMesh& mesh() const { return mesh_; }

 private:
  struct Node {
    double g = 0;
    Vec2 at;
    std::int32_t parent = -1;
    std::int32_t into = -1;   // polygon entered through this portal
    std::uint32_t stamp = 0;  // == generation_: open, == generation_ + 1: closed
  };
  struct Entry {
    double f, g;
    std::int32_t node;  // portal index, or the goal (portals().size())
  };

  void relax(std::int32_t portal, std::int32_t parent, Vec2 from, double g, std::int32_t into,
             Vec2 goal);
  void push(const Entry& e);
  Entry pop();

  const NavMesh& mesh_;
  std::vector<Node> nodes_;
  std::vector<Entry> heap_;
  std::vector<std::int32_t> trail_;
  std::uint32_t generation_ = 0;
  int expanded_ = 0;
};

}  // namespace zonesim::ai
