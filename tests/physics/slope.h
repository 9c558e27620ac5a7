#pragma once
// The friction check shared by the solver tests: a cube on a 30-degree slope.

#include <numbers>

#include "physics/world.h"

namespace zonesim::physics::testing {

/// Distance a unit cube, set at rest on a static plane tilted 30 degrees about z, travels along
/// it in 2 s (120 steps of 1/60 s) with friction mu on both. Theory: none where mu >= tan 30,
/// else a t^2 / 2 with a = g (sin 30 - mu cos 30).
inline double slideOnSlope(const WorldSettings& settings, double mu) {
  const Quat tilt(Eigen::AngleAxisd(std::numbers::pi / 6.0, Vec3::UnitZ()));
  const Vec3 n = tilt * Vec3::UnitY();
  World world(settings);
  BodyDesc slope;
  slope.type = BodyType::Static;
  slope.shape = Shape::plane();
  slope.orientation = tilt;
  slope.friction = mu;
  world.addBody(slope);
  BodyDesc box;
  box.shape = Shape::box(Vec3(0.5, 0.5, 0.5));
  box.orientation = tilt;
  box.position = 0.5 * n;
  box.friction = mu;
  const BodyIndex i = world.addBody(box);
  for (int step = 0; step < 120; ++step) world.step(1.0 / 60.0);
  return (world.bodies().position[i] - 0.5 * n).norm();
}

}  // namespace zonesim::physics::testing
