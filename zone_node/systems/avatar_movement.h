#pragma once
// Player avatars: move in the direction of the last applied input at the avatar's speed (its
// kind's), walkers and riders on the ground, flyers at their kind's height.

#include "common/scene_geometry.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// Acceleration that lets an avatar reach full speed in about a quarter of a second.
constexpr double kAvatarAccel = 24.0;

/// Steps every avatar of the store by dt, keeping it inside the world.
void stepAvatars(const SceneBox& world, EntityStore& store, double dt);

}  // namespace zonesim::zone
