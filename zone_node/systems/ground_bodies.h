#pragma once
// The thin physics of the foundation: spheres under gravity with semi-implicit Euler, bouncing
// on the ground plane and the world's side walls with restitution, rolling friction on the
// ground, and sleeping once at rest (a sleeping body costs one branch). The full rigid-body
// engine (zone_node/physics/) replaces this.

#include "common/scene.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

constexpr double kGravity = 9.81;
/// Below this speed on the ground a body falls asleep.
constexpr double kSleepSpeed = 0.05;

/// Steps every awake rigid body by dt; returns how many are still awake.
std::size_t stepGroundBodies(const SceneBox& world, EntityStore& store, double dt);

}  // namespace zonesim::zone
