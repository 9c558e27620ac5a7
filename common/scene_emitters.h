#pragma once
// Particle emitter populations of a scene (`populations:` entries of kind particle_emitter).

#include "common/scene_geometry.h"

namespace zonesim {

/// Particle emitters: each spawns `rate` particles per second with the given lifetime.
struct EmitterPopulation {
  int count = 0;
  double rate = 100;      ///< particles per second per emitter
  double lifetime = 2.0;  ///< seconds
  double speed = 5.0;     ///< initial speed, m/s, upward cone
  double restitution = 0.4;
  double drag = 0.1;         ///< linear drag coefficient, 1/s
  int max_particles = 4096;  ///< per emitter; the oldest are recycled first
  SceneBox region;           ///< where the emitters stand (defaults to the world)
};

}  // namespace zonesim
