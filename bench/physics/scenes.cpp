#include "scenes.h"

namespace zonesim::physics::bench {

Scene pyramidScene() {
  Scene s;
  s.friction = 0.2;
  s.damping = 0.05;
  s.bodies.push_back(SceneBody{true, true, Vec3(50, 1, 50), 0.0, Vec3(0, -1, 0), Vec3(0, -1, 0)});
  constexpr int kHeight = 15;
  for (int i = 0; i < kHeight; ++i) {
    // Level i holds (15 - i)^2 boxes; odd levels sit 1 m over in x and z (as in Jolt).
    for (int j = i / 2; j < kHeight - (i + 1) / 2; ++j) {
      for (int k = i / 2; k < kHeight - (i + 1) / 2; ++k) {
        const double shift = (i & 1) ? 1.0 : 0.0;
        const double x = -kHeight + 2.0 * j + shift, z = -kHeight + 2.0 * k + shift;
        s.bodies.push_back(SceneBody{true, false, Vec3(1, 1, 1), 0.0, Vec3(x, 1.0 + 2.5 * i, z),
                                     Vec3(x, 1.0 + 2.0 * i, z)});
      }
    }
  }
  return s;
}

namespace {

// One 2D pyramid of boxes of half extent h in the plane z = z0: level i holds base - i boxes,
// centred at y = (2i + 1) h, spaced 2h in x, each level shifted h along x (Box3D's layout).
void addBoxPyramid(Scene& s, int base, double h, double x0, double z0) {
  for (int i = 0; i < base; ++i) {
    const double y = (2.0 * i + 1.0) * h;
    for (int j = i; j < base; ++j) {
      const Vec3 p(x0 + (i + 1.0) * h + 2.0 * (j - i) * h, y, z0);
      s.bodies.push_back(SceneBody{true, false, Vec3::Constant(h), 0.0, p, p});
    }
  }
}

}  // namespace

Scene largePyramidScene(int base) {
  Scene s;
  s.friction = 0.6;  // Box3D's default shape friction.
  s.density = 100.0;
  s.bodies.push_back(SceneBody{true, true, Vec3(400, 1, 400), 0.0, Vec3(0, -1, 0), Vec3(0, -1, 0)});
  constexpr double h = 0.5;
  addBoxPyramid(s, base, h, -h * base, 0.0);
  return s;
}

Scene manyPyramidsScene(int rows, int columns, int base) {
  Scene s;
  s.friction = 0.6;
  s.density = 100.0;
  constexpr double h = 0.5;
  const double ground = h * columns * (base + 1.0);
  s.bodies.push_back(
      SceneBody{true, true, Vec3(ground, 1, ground), 0.0, Vec3(0, -1, 0), Vec3(0, -1, 0)});
  const double base_width = 2.0 * h * base;
  const double dz = rows > 1 ? 2.0 * (ground - 2.0 * h) / (rows - 1.0) : 0.0;
  double z = -ground + 2.0 * h;
  for (int r = 0; r < rows; ++r, z += dz) {
    for (int c = 0; c < columns; ++c) {
      const double centre_x = -ground + c * (base_width + 2.0 * h) + 2.0 * h;
      addBoxPyramid(s, base, h, centre_x - 0.5, z);
    }
  }
  return s;
}

Scene spheresScene() {
  Scene s;
  s.friction = 0.5;
  s.bodies.push_back(SceneBody{true, true, Vec3(25, 1, 25), 0.0, Vec3(0, -1, 0), Vec3::Zero()});
  // Walls 20 m high with inner faces at +-20.
  const Vec3 wall_x(0.5, 10, 21), wall_z(21, 10, 0.5);
  s.bodies.push_back(SceneBody{true, true, wall_x, 0.0, Vec3(-20.5, 10, 0), Vec3::Zero()});
  s.bodies.push_back(SceneBody{true, true, wall_x, 0.0, Vec3(20.5, 10, 0), Vec3::Zero()});
  s.bodies.push_back(SceneBody{true, true, wall_z, 0.0, Vec3(0, 10, -20.5), Vec3::Zero()});
  s.bodies.push_back(SceneBody{true, true, wall_z, 0.0, Vec3(0, 10, 20.5), Vec3::Zero()});
  for (int layer = 0; layer < 8; ++layer) {
    const double shift = (layer & 1) ? 0.375 : 0.0;
    for (int i = 0; i < 25; ++i) {
      for (int k = 0; k < 25; ++k) {
        const Vec3 p(-18 + 1.5 * i + shift, 1 + 1.5 * layer, -18 + 1.5 * k + shift);
        s.bodies.push_back(SceneBody{false, false, Vec3::Zero(), 0.5, p, p});
      }
    }
  }
  return s;
}

}  // namespace zonesim::physics::bench
