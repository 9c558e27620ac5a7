#pragma once
// Hand-placed physics objects of a scene (physics.bodies, joints, cloths, explosions): their
// reader, kept apart from scene_loader.cpp. Internal to the scene loader.

#include "common/scene_loader_node.h"

namespace zonesim {

struct Scene;

/// Reads physics.bodies, .joints, .cloths and .explosions into scene.physics; `root` is the
/// document's top-level mapping (its physics keys already checked), scene.world and
/// scene.zones already read.
void readPhysicsObjects(const SceneMap& root, Scene& scene);

struct PhysicsSettings;

/// Refuses rolling resistance under a solver the scene named that cannot solve it: projection
/// (no velocities) and the wide soft step. `m` holds the body's or population's keys.
void checkRollingSolver(const SceneMap& m, double rolling_resistance, const PhysicsSettings& ps);

/// The default solver, the wide soft step, gives way to the soft step where a scene that names
/// no solver has a body or population with rolling resistance. Called once all are read.
void resolveDefaultSolver(Scene& scene);

}  // namespace zonesim
