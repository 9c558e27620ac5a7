#pragma once
// Planar steering shared by walking NPCs and avatars: accelerate toward a desired velocity
// with bounded acceleration, then integrate with semi-implicit Euler (velocity first).

#include <algorithm>

#include "common/math.h"
#include "common/scene_geometry.h"

namespace zonesim::zone {

/// Advances (pos, vel) one step toward `desired` velocity with at most `accel` m/s^2.
inline void steerAndIntegrate(Vec3& pos, Vec3& vel, const Vec3& desired, double accel, double dt) {
  Vec3 dv = desired - vel;
  double max_dv = accel * dt;
  double n = dv.norm();
  if (n > max_dv) dv *= max_dv / n;
  vel += dv;
  pos += vel * dt;
}

/// Walkers stay on the world's ground: clamp x-z to the world and stop motion into its walls.
inline void keepOnGround(const SceneBox& world, Vec3& pos, Vec3& vel) {
  auto wall = [](double& p, double& v, double lo, double hi) {
    if (p < lo) {
      p = lo;
      v = std::max(v, 0.0);
    }
    if (p > hi) {
      p = hi;
      v = std::min(v, 0.0);
    }
  };
  wall(pos.x(), vel.x(), world.min.x, world.max.x);
  wall(pos.z(), vel.z(), world.min.z, world.max.z);
}

/// Flyers hold their height above the ground with no vertical motion: nothing pulls them down,
/// and the state clients extrapolate carries no climb or sink.
inline void holdHeight(const SceneBox& world, double height, Vec3& pos, Vec3& vel) {
  pos.y() = world.min.y + height;
  vel.y() = 0;
}

/// Orientation facing along the planar velocity (yaw about +y); unchanged when standing still.
inline Quat facing(const Quat& current, const Vec3& vel) {
  double speed2 = vel.x() * vel.x() + vel.z() * vel.z();
  if (speed2 < 1e-8) return current;
  double yaw = std::atan2(vel.x(), vel.z());
  return Quat(Eigen::AngleAxisd(yaw, Vec3::UnitY()));
}

}  // namespace zonesim::zone
