#pragma once
// The restitution check shared by the solver tests: a ball dropped onto a plane.

#include <algorithm>

#include "physics/world.h"

namespace zonesim::physics::testing {

/// Drops a ball of radius r from gap h onto a static plane, both with restitution e, and steps
/// 2,500 steps of dt; returns the highest gap the ball reaches after it first moves up (the
/// rebound apex; theory: e^2 h).
inline double reboundApex(const WorldSettings& settings, double h, double e, double r, double dt) {
  World world(settings);
  BodyDesc ground;
  ground.type = BodyType::Static;
  ground.shape = Shape::plane();
  ground.restitution = e;
  world.addBody(ground);
  BodyDesc ball;
  ball.shape = Shape::sphere(r);
  ball.position = Vec3(0, r + h, 0);
  ball.restitution = e;
  const BodyIndex i = world.addBody(ball);
  bool bounced = false;
  double apex = 0.0;
  for (int step = 0; step < 2500; ++step) {
    world.step(dt);
    bounced = bounced || world.bodies().linear_velocity[i].y() > 0.0;
    if (bounced) apex = std::max(apex, world.bodies().position[i].y() - r);
  }
  return apex;
}

}  // namespace zonesim::physics::testing
