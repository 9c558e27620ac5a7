#pragma once
// The scene's static and kinematic bodies (physics.bodies with motion: static or kinematic):
// scene geometry, not entities. Every zone adds all of them to its engine world, so a dynamic
// body meets the same ramp or moving platform whichever zone holds it, and nothing about them
// needs to travel between ranks. A kinematic body's pose is a closed form of the tick,
// p0 + v t and exp(w t) q0, set before each step: every rank computes the same bits at the
// same tick however often its world was rebuilt (an integrated pose would depend on that).
// Clients know them from the scene file; they are not published.

#include <cstdint>
#include <optional>
#include <vector>

#include "physics/body_storage.h"

namespace zonesim {
struct PhysicsSettings;
}  // namespace zonesim

namespace zonesim::physics {
class World;
}

namespace zonesim::zone {

class SetPieces {
 public:
  /// The set pieces among `physics.bodies` (the scene's, which must outlive this).
  explicit SetPieces(const PhysicsSettings& physics);

  /// Adds every static and kinematic scene body to `world`, posed for tick 0, in scene order.
  void addTo(physics::World& world);
  /// Poses the kinematic bodies for the start of tick k (time k dt) and wakes the moving ones.
  void pose(physics::World& world, std::uint64_t k, double dt) const;
  /// The world index of scene body k if it is a set piece (after addTo), else nothing.
  std::optional<physics::BodyIndex> indexOf(std::size_t k) const;
  /// How many bodies addTo adds.
  std::size_t count() const { return scene_body_.size(); }
  /// True if some kinematic body moves, so the world must be stepped even when all sleep.
  bool moving() const { return moving_; }

 private:
  const PhysicsSettings& physics_;
  std::vector<std::size_t> scene_body_;    // set piece n -> index into scene.physics.bodies
  std::vector<physics::BodyIndex> index_;  // set piece n -> world index (after addTo)
  bool moving_ = false;
};

}  // namespace zonesim::zone
