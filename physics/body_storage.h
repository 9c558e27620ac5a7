#pragma once
// Bodies as a structure of arrays, indexed by body index (creation order). Hot loops walk one
// or two arrays at a time; nothing here is virtual.

#include <cstdint>
#include <vector>

#include "common/math.h"
#include "physics/body.h"

namespace zonesim::physics {

/// Index of a body in the world's arrays, stable for the body's life.
using BodyIndex = std::uint32_t;

/// The state of every body, one array per component.
struct BodyStorage {
  std::vector<BodyType> type;
  std::vector<Shape> shape;
  std::vector<Vec3> position;
  std::vector<Quat> orientation;
  std::vector<Vec3> linear_velocity;
  std::vector<Vec3> angular_velocity;
  std::vector<Vec3> force;   ///< Applied this step; cleared after it.
  std::vector<Vec3> torque;  ///< Applied this step; cleared after it.
  std::vector<double> inv_mass;
  /// Inverse inertia tensor in the body frame: diagonal for a sphere, box or capsule, full for
  /// a compound.
  std::vector<Eigen::Matrix3d> inv_inertia_local;
  std::vector<Eigen::Matrix3d> inv_inertia_world;  ///< R inv_inertia_local R^T.
  std::vector<double> friction;
  std::vector<double> restitution;
  std::vector<double> rolling_resistance;
  std::vector<double> linear_damping;
  std::vector<double> angular_damping;
  std::vector<Vec3> position_prev;  ///< Position Verlet history.

  /// Appends a body and returns its index.
  BodyIndex add(const BodyDesc& desc);
  /// Number of bodies.
  std::size_t size() const { return type.size(); }
  /// Recomputes every world-space inverse inertia from the current orientations.
  void updateWorldInertia();
};

}  // namespace zonesim::physics
