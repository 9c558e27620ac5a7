#include "physics/body_storage.h"

#include "physics/mass_properties.h"

namespace zonesim::physics {

namespace {

/// The inverse of an inertia tensor; a diagonal one inverted element by element, exactly.
Eigen::Matrix3d inverseInertia(const Eigen::Matrix3d& inertia) {
  const Eigen::Matrix3d off = inertia - Eigen::Matrix3d(inertia.diagonal().asDiagonal());
  if (off.isZero(0.0)) return inertia.diagonal().cwiseInverse().asDiagonal();
  return inertia.inverse();
}

}  // namespace

BodyIndex BodyStorage::add(const BodyDesc& desc) {
  const auto index = static_cast<BodyIndex>(size());
  const bool moves_by_forces = desc.type == BodyType::Dynamic || desc.type == BodyType::Particle;
  const MassProperties mp = computeMassProperties(desc.shape, desc.density);
  double w = 0.0;
  Eigen::Matrix3d inv_inertia = Eigen::Matrix3d::Zero();
  if (moves_by_forces && mp.mass > 0.0) {
    w = 1.0 / mp.mass;
    // Particles never rotate: infinite inertia.
    if (desc.type == BodyType::Dynamic) inv_inertia = inverseInertia(mp.inertia);
  }
  const bool still = desc.type == BodyType::Static;
  type.push_back(desc.type);
  shape.push_back(desc.shape);
  position.push_back(desc.position);
  orientation.push_back(desc.orientation.normalized());
  linear_velocity.push_back(still ? Vec3::Zero() : desc.linear_velocity);
  angular_velocity.push_back(still || desc.type == BodyType::Particle ? Vec3::Zero()
                                                                      : desc.angular_velocity);
  force.push_back(Vec3::Zero());
  torque.push_back(Vec3::Zero());
  inv_mass.push_back(w);
  inv_inertia_local.push_back(inv_inertia);
  inv_inertia_world.push_back(Eigen::Matrix3d::Zero());
  friction.push_back(desc.friction);
  restitution.push_back(desc.restitution);
  rolling_resistance.push_back(desc.rolling_resistance);
  linear_damping.push_back(desc.linear_damping);
  angular_damping.push_back(desc.angular_damping);
  position_prev.push_back(desc.position);
  const Eigen::Matrix3d r = orientation.back().toRotationMatrix();
  inv_inertia_world.back() = r * inv_inertia * r.transpose();
  return index;
}

void BodyStorage::updateWorldInertia() {
  const std::size_t n = size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Matrix3d r = orientation[i].toRotationMatrix();
    inv_inertia_world[i] = r * inv_inertia_local[i] * r.transpose();
  }
}

}  // namespace zonesim::physics
