#pragma once
// The stack scene the tests and benchmarks share: a column of unit cubes (friction 0.5) resting
// on a static 100 m x 2 m x 100 m floor box whose top is y = 0, stepped at 60 Hz. One builder,
// so that "the 20-box stack" means the same bodies in every test, sweep and work-precision run.

#include <span>
#include <vector>

#include "common/math.h"
#include "physics/world.h"

namespace zonesim::physics {

class BoxColumn {
 public:
  /// One cube per density (kg/m^3), bottom to top.
  BoxColumn(const WorldSettings& settings, std::span<const double> densities);

  /// Steps round(seconds * 60) steps of 1/60 s.
  void run(double seconds);
  /// Largest displacement of any cube from its start: on the ground plane, vertically, and in
  /// all.
  struct Drift {
    double horizontal = 0, vertical = 0, total = 0;
  };
  Drift drift() const;
  /// Height of the top cube's centre.
  double topHeight() const;
  World& world() { return world_; }
  const World& world() const { return world_; }

 private:
  World world_;
  std::vector<Vec3> start_;  // cube k is body k + 1 (the floor is body 0)
};

}  // namespace zonesim::physics
