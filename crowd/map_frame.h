#pragma once
// Where a GridMap lies in the world: the corner of cell (0, 0) and the side of a cell. Agents
// move continuously; the grid answers which cell a point is in, and moves are kept off blocked
// cells by sliding along walls (no step ever enters a blocked cell or cuts a blocked corner).

#include "ai/grid_map.h"
#include "ai/vec2.h"
#include "crowd/vec2.h"

namespace zonesim::crowd {

/// Placement of a grid map in the world plane.
struct MapFrame {
  Vec2 origin;             ///< world position of the outer corner of cell (0, 0)
  double cell_size = 1.0;  ///< side of one cell in metres

  /// Cell containing `p` (may lie off the map).
  ai::Cell cellOf(Vec2 p) const {
    return ai::Cell{int(std::floor((p.x - origin.x) / cell_size)),
                    int(std::floor((p.y - origin.y) / cell_size))};
  }
  /// World position of a cell's centre.
  Vec2 centre(ai::Cell c) const {
    return Vec2{origin.x + (c.x + 0.5) * cell_size, origin.y + (c.y + 0.5) * cell_size};
  }
  /// A world point in map units (cell (x, y) covers [x, x+1) x [y, y+1): the navigation mesh's).
  ai::Vec2 toMap(Vec2 p) const {
    return ai::Vec2{(p.x - origin.x) / cell_size, (p.y - origin.y) / cell_size};
  }
  /// A point in map units in the world.
  Vec2 toWorld(double x, double y) const {
    return Vec2{origin.x + x * cell_size, origin.y + y * cell_size};
  }
};

/// True when `p` lies on a passable cell.
bool walkable(const ai::GridMap& map, const MapFrame& frame, Vec2 p);

/// The move from `from` (walkable) toward `to`, short of one cell: `to` when that is walkable
/// and reached without cutting a blocked corner, else the axis-aligned part that is (sliding
/// along the wall), else `from`. `vel` loses the blocked components.
Vec2 slideMove(const ai::GridMap& map, const MapFrame& frame, Vec2 from, Vec2 to, Vec2& vel);

/// True when the straight segment a-b crosses only passable cells (an exact grid traversal
/// that also rejects a segment passing through the shared corner of two blocked cells).
bool lineOfSight(const ai::GridMap& map, const MapFrame& frame, Vec2 a, Vec2 b);

}  // namespace zonesim::crowd
