#pragma once
// A path on a grid: the cells from start to goal inclusive and its length; a navigation-mesh
// path also keeps its any-angle corner points.

#include <vector>

#include "ai/octile.h"
#include "ai/vec2.h"

namespace zonesim::ai {

class GridMap;

/// Cells from start to goal inclusive; empty when there is no path.
struct GridPath {
  /// Start first, goal last; for a navmesh path, every cell its segments touch (walls they
  /// graze included), in order along it, so that a closed cell finds the paths it may cut.
  std::vector<Cell> cells;
  double length = 0.0;  ///< sum of step costs (1 or sqrt(2)), or of the navmesh segments
  /// Navmesh paths only: the corner points, start first, goal last, in map units.
  std::vector<Vec2> points;
  /// Empties the path but keeps its capacity (no allocation on reuse).
  void clear() {
    cells.clear();
    points.clear();
    length = 0.0;
  }
};

/// A half-open rectangle of cells [x0, x1) x [y0, y1) that a search may not leave.
struct CellRect {
  int x0 = 0;  ///< first column
  int y0 = 0;  ///< first row
  int x1 = 0;  ///< one past the last column
  int y1 = 0;  ///< one past the last row
  /// True when (x, y) is inside.
  bool contains(int x, int y) const { return x >= x0 && y >= y0 && x < x1 && y < y1; }
};

/// Sum of step costs along a cell sequence; steps must be between 8-neighbours.
double pathLength(const std::vector<Cell>& cells);

/// True when every step is an 8-neighbour move between passable cells without corner cutting.
bool isValidPath(const GridMap& map, const std::vector<Cell>& cells);

}  // namespace zonesim::ai
