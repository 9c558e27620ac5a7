#pragma once
// The benchmark scenes of issue 3, as engine-neutral lists of boxes and spheres.

#include <vector>

#include "common/math.h"

namespace zonesim::physics::bench {

/// One body of a scene: a box (half extents) or a sphere (radius), static or dynamic.
struct SceneBody {
  bool is_box = true;
  bool is_static = false;
  Vec3 half = Vec3::Zero();
  double radius = 0.0;
  Vec3 position = Vec3::Zero();
  Vec3 rest = Vec3::Zero();  ///< Ideal resting place (pyramid: gaps closed).
};

/// A scene with its material and step settings.
struct Scene {
  std::vector<SceneBody> bodies;
  double friction = 0.5;
  double damping = 0.0;
  double density = 1000.0;  ///< kg/m^3 of every dynamic body.
};

/// Jolt's PerformanceTest "Pyramid": 1,240 boxes of 2 m in 15 levels on a 100x2x100 floor.
Scene pyramidScene();
/// Box3D's large_pyramid: a 2D pyramid of unit boxes in the x-y plane, `base` boxes at the
/// bottom (100: 5,050 boxes), density 100, on a 400 x 2 x 400 ground box. Boxes start touching,
/// so each box's start is its rest place.
Scene largePyramidScene(int base = 100);
/// Box3D's many_pyramids: 14 x 14 small pyramids of base 10 (10,780 unit boxes, density 100).
Scene manyPyramidsScene(int rows = 14, int columns = 14, int base = 10);
/// 5,000 spheres of radius 0.5 dropped into an open box with walls at x, z = +-20.
Scene spheresScene();

}  // namespace zonesim::physics::bench
