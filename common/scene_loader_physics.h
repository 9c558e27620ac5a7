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

}  // namespace zonesim
