#pragma once
// A point or direction on the ground plane, in map units (cell (x, y) covers [x, x+1) x [y, y+1)).

namespace zonesim::ai {

/// A point or direction on the ground plane.
struct Vec2 {
  double x = 0.0;  ///< first coordinate
  double y = 0.0;  ///< second coordinate
  /// Points compare by coordinates.
  friend bool operator==(const Vec2&, const Vec2&) = default;
};

}  // namespace zonesim::ai
