#pragma once
// Move costs on an 8-connected grid: cardinal 1, diagonal sqrt(2) (the Moving AI convention).

#include <cmath>
#include <cstdint>
#include <cstdlib>

namespace zonesim::ai {

/// Cost of one diagonal step.
inline constexpr double kDiagonalCost = 1.4142135623730951;

/// A grid cell; x is the column, y the row, (0,0) top-left.
struct Cell {
  int x = 0;  ///< column
  int y = 0;  ///< row
  /// Cells compare by coordinates.
  friend bool operator==(const Cell&, const Cell&) = default;
};

/// Octile distance: the exact cost between two cells on an empty grid, hence admissible.
inline double octileDistance(int dx, int dy) {
  dx = std::abs(dx);
  dy = std::abs(dy);
  int lo = dx < dy ? dx : dy;
  int hi = dx < dy ? dy : dx;
  return double(hi - lo) + kDiagonalCost * double(lo);
}

/// Octile distance between two cells.
inline double octileDistance(Cell a, Cell b) {
  return octileDistance(a.x - b.x, a.y - b.y);
}

/// True when two results agree within the scenario tolerance (1e-3 relative, 1e-3 absolute
/// near zero, since lengths are printed rounded).
inline bool lengthsAgree(double a, double b) {
  double scale = std::fabs(b) > 1.0 ? std::fabs(b) : 1.0;
  return std::fabs(a - b) <= 1e-3 * scale;
}

}  // namespace zonesim::ai
