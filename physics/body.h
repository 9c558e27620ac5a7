#pragma once
// Body kinds and the description a body is created from.

#include <cstdint>

#include "common/math.h"
#include "physics/shape.h"

namespace zonesim::physics {

/// Particles translate only; statics never move; kinematics follow their set velocity and push
/// others without being pushed; dynamics respond to forces and contacts.
enum class BodyType : std::uint8_t { Particle, Static, Kinematic, Dynamic };

/// Everything needed to create a body; mass and inertia follow from shape and density.
struct BodyDesc {
  BodyType type = BodyType::Dynamic;
  Shape shape = Shape::sphere(0.5);
  Vec3 position = Vec3::Zero();
  Quat orientation = Quat::Identity();
  Vec3 linear_velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  double density = 1000.0;       ///< kg/m^3.
  double friction = 0.5;         ///< Coulomb coefficient; a pair uses the geometric mean.
  double restitution = 0.0;      ///< A pair uses the larger of the two.
  /// Rolling resistance coefficient c_rr (dimensionless, like friction): a rolling sphere or
  /// capsule of radius R pressed with normal force N meets a torque of at most c_rr R N
  /// against its rolling relative to what it touches. A pair uses the larger coefficient.
  double rolling_resistance = 0.0;
  double linear_damping = 0.0;   ///< 1/s: v *= 1 / (1 + c dt) each step.
  double angular_damping = 0.0;  ///< 1/s: w *= 1 / (1 + c dt) each step.
};

}  // namespace zonesim::physics
