#include "zone_node/systems/ground_bodies.h"

#include <cmath>

#include "common/math.h"

namespace zonesim::zone {

namespace {
/// Keeps a coordinate inside [lo + r, hi - r], reflecting the velocity with restitution e.
void bounceInside(double& x, double& v, double lo, double hi, double r, double e) {
  if (x < lo + r) {
    x = lo + r + (lo + r - x) * e;
    if (v < 0) v = -v * e;
  } else if (x > hi - r) {
    x = hi - r - (x - (hi - r)) * e;
    if (v > 0) v = -v * e;
  }
}
}  // namespace

std::size_t stepGroundBodies(const SceneBox& world, EntityStore& store, double dt) {
  std::size_t awake = 0;
  const double ground = world.min.y;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::RigidBody) continue;
    BodyData& b = store.body[i];
    if (b.sleeping) continue;
    Vec3& p = store.pos[i];
    Vec3& v = store.vel[i];
    v.y() -= kGravity * dt;
    p += v * dt;
    bounceInside(p.y(), v.y(), ground, world.max.y, b.radius, b.restitution);
    bounceInside(p.x(), v.x(), world.min.x, world.max.x, b.radius, b.restitution);
    bounceInside(p.z(), v.z(), world.min.z, world.max.z, b.radius, b.restitution);
    bool on_ground = p.y() <= ground + b.radius + 1e-3 && std::abs(v.y()) < 2 * kGravity * dt;
    if (on_ground) {
      // Rolling resistance: the body rolls without slipping, w = v x n / r.
      double damp = std::max(0.0, 1.0 - 0.8 * dt);
      v.x() *= damp;
      v.z() *= damp;
      b.angular_velocity = Vec3(v.z(), 0.0, -v.x()) / b.radius;
      if (v.norm() < kSleepSpeed) {
        v.setZero();
        p.y() = ground + b.radius;
        b.angular_velocity.setZero();
        b.sleeping = true;
        continue;
      }
    }
    store.rot[i] = integrateOrientation(store.rot[i], b.angular_velocity, dt);
    ++awake;
  }
  return awake;
}

}  // namespace zonesim::zone
