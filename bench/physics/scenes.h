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
};

/// Jolt's PerformanceTest "Pyramid": 1,240 boxes of 2 m in 15 levels on a 100x2x100 floor.
Scene pyramidScene();
/// 5,000 spheres of radius 0.5 dropped into an open box with walls at x, z = +-20.
Scene spheresScene();

}  // namespace zonesim::physics::bench
