#pragma once
// Plain geometry of scene data: points, boxes and rotations as the scene file gives them.
// Kept free of Eigen and of every other section, since most sections and many headers use it.

namespace zonesim {

/// Plain 3-vector for scene data (keeps Eigen out of this widely included header).
struct SceneVec3 {
  double x = 0, y = 0, z = 0;
};

/// An axis-aligned box, y up; the ground plane is x-z.
struct SceneBox {
  SceneVec3 min, max;
};

/// A unit quaternion (w, x, y, z); the identity by default.
struct SceneQuat {
  double w = 1, x = 0, y = 0, z = 0;
};

/// A point on the ground plane given in the scene; `line` is where (for errors on loading).
struct ScenePoint {
  double x = 0, z = 0;
  int line = 0;
};

}  // namespace zonesim
