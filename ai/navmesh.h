#pragma once
// A navigation mesh built from a grid map: convex polygons that bound the walkable regions by
// the shape of the environment, joined by portals. The agent radius is taken into account by
// erosion only: a cell stays on the mesh when its whole square lies at least `agent_radius`
// from every blocked cell and from the map's edge, so every point of the mesh has that
// clearance and a path anywhere on it keeps an agent's disc off the walls; portals are
// therefore used whole (the funnel does not shrink them again). The walkable cells are then
// merged greedily into maximal axis-aligned rectangles (row-major seeds, widest run first,
// then as many rows as fit), which are convex and disjoint; a portal is the segment two
// rectangles share. Coordinates are map units: cell (x, y) covers [x, x+1) x [y, y+1), so
// every vertex is a lattice point. Static boxes (NavBox) are closed on a copy of the grid
// before erosion.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "ai/vec2.h"

namespace zonesim::ai {

/// Build settings.
struct NavMeshConfig {
  double agent_radius = 0.0;  ///< clearance kept from walls, map units (cells); >= 0
};

/// An axis-aligned static obstacle's footprint in map units: closes every cell whose square it
/// overlaps with positive area.
struct NavBox {
  double x0 = 0, y0 = 0;  ///< lower corner
  double x1 = 0, y1 = 0;  ///< upper corner
};

/// A convex polygon of the mesh: the cells [x0, x1) x [y0, y1).
struct NavPolygon {
  int x0 = 0, y0 = 0;  ///< first column and row
  int x1 = 0, y1 = 0;  ///< one past the last column and row
};

/// The segment two polygons share: from (x0, y0) to (x1, y1), horizontal or vertical, of
/// positive length. `low` is the polygon with the smaller coordinate across the portal.
struct NavPortal {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  ///< end points (x0 <= x1, y0 <= y1)
  std::int32_t low = -1;               ///< polygon left of (vertical) or above (horizontal)
  std::int32_t high = -1;              ///< the polygon on the other side
  /// The polygon across the portal from `from`.
  std::int32_t other(std::int32_t from) const { return from == low ? high : low; }
};

/// Convex polygons and portals over one grid map.
class NavMesh {
 public:
  /// Builds the mesh of `map`; throws std::invalid_argument for a negative or non-finite radius.
  NavMesh(const GridMap& map, const NavMeshConfig& config);
  /// As above with `boxes` closed on a copy of the grid first.
  NavMesh(const GridMap& map, const std::vector<NavBox>& boxes, const NavMeshConfig& config);

  /// The polygons, in the order they were seeded (row-major by top-left cell).
  const std::vector<NavPolygon>& polygons() const { return polygons_; }
  /// The portals, each listed once.
  const std::vector<NavPortal>& portals() const { return portals_; }
  /// Portal indices of polygon p, in the order they were found.
  const std::int32_t* portalsBegin(int p) const { return adjacency_.data() + offsets_[p]; }
  /// One past the last portal index of polygon p.
  const std::int32_t* portalsEnd(int p) const { return adjacency_.data() + offsets_[p + 1]; }
  /// Polygon holding cell (x, y), or -1 when the cell is off the mesh (blocked or eroded).
  int polygonAt(int x, int y) const;
  /// Polygon holding point p (the cell it falls in), or -1.
  int polygonAt(Vec2 p) const;
  /// Map width and height, cells.
  int width() const { return width_; }
  /// Map height, cells.
  int height() const { return height_; }
  /// The settings it was built with.
  const NavMeshConfig& config() const { return config_; }
  /// Bytes held by the mesh (polygons, portals, adjacency and the per-cell polygon index).
  std::size_t memoryBytes() const;

 private:
  void build(const GridMap& map);

  NavMeshConfig config_;
  int width_ = 0, height_ = 0;
  std::vector<NavPolygon> polygons_;
  std::vector<NavPortal> portals_;
  std::vector<std::int32_t> offsets_;    // polygon p's portals: adjacency_[offsets_[p]..[p+1])
  std::vector<std::int32_t> adjacency_;  // portal indices
  std::vector<std::int32_t> cell_polygon_;
};

/// Closes, on `map`, every cell whose square overlaps a box with positive area.
void closeBoxes(GridMap& map, const std::vector<NavBox>& boxes);

/// The cells left walkable for an agent of `radius` (1: on the mesh), row-major: passable cells
/// whose square lies at least `radius` from every blocked cell and from outside the map.
std::vector<std::uint8_t> erodeWalkable(const GridMap& map, double radius);

}  // namespace zonesim::ai
