#include "zone_node/systems/set_pieces.h"

#include <algorithm>

#include "common/scene_physics.h"
#include "physics/world.h"
#include "zone_node/systems/scene_shapes.h"

namespace zonesim::zone {

namespace {

/// exp(w t) q0: the orientation after turning at the constant world angular velocity w.
Quat turned(const SceneBody& b, double t) {
  const Vec3 w = toVec3(b.angular_velocity);
  const double rate = w.norm();
  if (rate == 0.0) return toQuat(b.orientation);
  return (Quat(Eigen::AngleAxisd(rate * t, w / rate)) * toQuat(b.orientation)).normalized();
}

}  // namespace

SetPieces::SetPieces(const PhysicsSettings& physics) : physics_(physics) {
  const std::vector<SceneBody>& bodies = physics.bodies;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    if (bodies[k].motion == SceneBody::Motion::Dynamic) continue;
    scene_body_.push_back(k);
    const bool still =
        toVec3(bodies[k].velocity).isZero(0) && toVec3(bodies[k].angular_velocity).isZero(0);
    moving_ = moving_ || (bodies[k].motion == SceneBody::Motion::Kinematic && !still);
  }
}

void SetPieces::addTo(physics::World& world) {
  index_.clear();
  for (std::size_t k : scene_body_) {
    const SceneBody& b = physics_.bodies[k];
    physics::BodyDesc d;
    d.type = b.motion == SceneBody::Motion::Static ? physics::BodyType::Static
                                                   : physics::BodyType::Kinematic;
    d.shape = sceneShape(b);
    d.position = toVec3(b.position);
    d.orientation = toQuat(b.orientation);
    if (d.type == physics::BodyType::Kinematic) {
      d.linear_velocity = toVec3(b.velocity);
      d.angular_velocity = toVec3(b.angular_velocity);
    }
    d.friction = b.friction;
    d.rolling_resistance = b.rolling_resistance;
    d.restitution = b.restitution;
    index_.push_back(world.addBody(d));
  }
}

void SetPieces::pose(physics::World& world, std::uint64_t k, double dt) const {
  physics::BodyStorage& s = world.bodies();
  const double t = double(k) * dt;
  for (std::size_t n = 0; n < scene_body_.size(); ++n) {
    const SceneBody& b = physics_.bodies[scene_body_[n]];
    if (b.motion != SceneBody::Motion::Kinematic) continue;
    const physics::BodyIndex i = index_[n];
    s.position[i] = toVec3(b.position) + t * toVec3(b.velocity);
    s.position_prev[i] = s.position[i];
    s.orientation[i] = turned(b, t);
    s.linear_velocity[i] = toVec3(b.velocity);
    s.angular_velocity[i] = toVec3(b.angular_velocity);
    if (!toVec3(b.velocity).isZero(0) || !toVec3(b.angular_velocity).isZero(0)) world.wake(i);
  }
}

std::optional<physics::BodyIndex> SetPieces::indexOf(std::size_t k) const {
  auto it = std::find(scene_body_.begin(), scene_body_.end(), k);
  if (it == scene_body_.end() || index_.empty()) return std::nullopt;
  return index_[std::size_t(it - scene_body_.begin())];
}

}  // namespace zonesim::zone
