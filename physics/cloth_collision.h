#pragma once
// Cloth against rigid bodies: after every cloth sub-step each particle closer than the cloth's
// thickness to a body's surface is put back on the surface (plus thickness), its velocity
// relative to the body loses its approaching normal part, and Coulomb friction removes up to
// mu times that from the sliding part. Bodies push cloth; the cloth's equal and opposite
// impulses are summed per body and handed to the dynamic ones afterwards (two-way), so the
// momentum of cloth and bodies together is conserved. Bodies keep their pose during the cloth's
// step (the world steps first), which lags a moving body's surface by at most its travel in
// one step.

#include <cstdint>
#include <vector>

#include "common/math.h"
#include "physics/body_storage.h"

namespace zonesim::physics {

class World;

/// Signed distance from point p to the surface of a shape at a pose (negative inside) and the
/// outward normal there. Planes are half-spaces (local +y out).
double signedDistance(const Shape& shape, const Vec3& position, const Quat& orientation,
                      const Vec3& p, Vec3& normal);

/// The bodies a cloth collides with, snapshot from a world, and the reactions the cloth gave.
class ClothColliders {
 public:
  /// Takes every body of the world (poses and velocities as they are now).
  void gather(const BodyStorage& bodies);
  /// Pushes particles out of the bodies and applies contact and friction velocity changes;
  /// called by Cloth::step after every sub-step.
  void resolve(std::vector<Vec3>& x, std::vector<Vec3>& v, const std::vector<double>& inv_mass,
               double thickness, double friction);
  /// Adds the cloth's summed reactions to the world's dynamic bodies (waking one only when the
  /// change in its velocity exceeds wake_speed) and clears them.
  void applyReactions(World& world, double wake_speed = 0.05);
  /// Particle-body contacts resolved since gather().
  std::size_t contacts() const { return contacts_; }

 private:
  struct Collider {
    BodyIndex body;
    Shape shape;
    Vec3 position, linear_velocity, angular_velocity;
    Quat orientation;
    double bound;  // radius of a sphere around position holding the shape (infinite: plane)
    bool dynamic;
  };
  std::vector<Collider> colliders_;
  std::vector<Vec3> impulse_, angular_impulse_;  // per collider, about its centre
  std::size_t contacts_ = 0;
};

}  // namespace zonesim::physics
