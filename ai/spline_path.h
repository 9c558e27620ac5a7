#pragma once
// Smooth movement along a path: a centripetal Catmull-Rom spline through the path's points
// (centripetal parametrisation never forms cusps or self-loops on sharp grid turns), walked at
// constant speed through an arc-length table built once per path.

#include <vector>

#include "ai/grid_path.h"
#include "ai/vec2.h"

namespace zonesim::ai {

/// Catmull-Rom spline (or a polyline) through control points, sampled by arc length.
class SplinePath {
 public:
  /// How the points are joined: a smooth curve for grid paths (cell centres), straight segments
  /// for navmesh corners, where a curve would bulge past the corner into the wall.
  enum class Curve { CatmullRom, Polyline };
  /// Builds the spline through `points` (at least one); `samplesPerSegment` sets the accuracy
  /// of the arc-length table.
  explicit SplinePath(std::vector<Vec2> points, int samplesPerSegment = 16,
                      Curve curve = Curve::CatmullRom);
  /// Cell centres of a grid path (cell (x, y) has centre (x + 0.5, y + 0.5)).
  static std::vector<Vec2> cellCentres(const GridPath& path);

  /// Point at parameter t in [0, segments()]; integer t are the control points.
  Vec2 at(double t) const;
  /// Point at arc length s from the start, clamped to [0, length()].
  Vec2 atDistance(double s) const;
  /// Approximate arc length of the whole spline.
  double length() const { return cumulative_.back(); }
  /// Number of segments (control points minus one).
  int segments() const { return int(points_.size()) - 1; }

 private:
  std::vector<Vec2> points_;
  int samples_;
  Curve curve_;
  std::vector<double> cumulative_;  // arc length at each table sample
};

/// Moves an agent along a spline at a fixed speed.
class SplineFollower {
 public:
  /// Starts at the beginning of `path` moving at `speed` units per second.
  SplineFollower(const SplinePath& path, double speed) : path_(path), speed_(speed) {}
  /// Advances by `dt` seconds and returns the new position.
  Vec2 advance(double dt);
  /// Current position.
  Vec2 position() const { return path_.atDistance(travelled_); }
  /// True once the end of the path is reached.
  bool arrived() const { return travelled_ >= path_.length(); }

 private:
  const SplinePath& path_;
  double speed_;
  double travelled_ = 0.0;
};

}  // namespace zonesim::ai
