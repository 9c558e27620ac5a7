#pragma once
// Flocking on the ground plane on an OpenCL device, with read-only ghosts: the rules of the
// crowd library's flock (crowd/flock.h: separation, alignment, cohesion, an optional
// goal velocity, bounded force and speed, per-agent dt and detail) in float, for zone flocks too
// large for the CPU. The crowd library's double flock is the reference (tests/gpu). A zone's
// flock lives in the zone's store and comes with new ghosts every tick, so each step uploads
// the agents already sorted into cells (an O(n) counting sort on the host, during the pass that
// converts them anyway) and reads back velocities. No OpenCL or Eigen header comes with it.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace zonesim::gpu {

class ClRuntime;

/// A point or vector on the ground plane (world x, z).
struct Vec2d {
  double x = 0;  ///< world x
  double y = 0;  ///< world z
};

/// The crowd flock's settings (crowd/flock.h's FlockSettings, same meaning and units).
struct PlanarFlockParams {
  double neighbour_radius = 3.0;    ///< m: alignment and cohesion see agents this close
  double separation_radius = 1.0;   ///< m: separation pushes apart agents closer than this
  double separation_weight = 20.0;  ///< 1/s^2 per unit of (radius / distance - 1)
  double alignment_weight = 1.0;    ///< 1/s
  double cohesion_weight = 0.5;     ///< 1/s^2
  double goal_weight = 1.0;         ///< 1/s: rate at which velocity follows the goal velocity
  double max_speed = 2.0;           ///< m/s
  double max_force = 8.0;           ///< m/s^2
};

/// One step's agents: owned ones (moved) and ghosts (seen only); ids unique across both. Sums
/// run in cell-then-id order on global cells, so a result does not depend on the order given
/// or on which other agents are present beyond the neighbour radius.
struct PlanarAgents {
  std::span<const std::uint64_t> ids;  ///< stable ids (break exact overlaps, as on the CPU)
  std::span<const Vec2d> pos;          ///< positions
  std::span<const Vec2d> vel;          ///< velocities
};

/// Optional per-agent inputs of a step, each empty or one entry per owned agent.
struct PlanarControls {
  std::span<const Vec2d> goal;          ///< goal velocities (empty: none)
  std::span<const double> dt;           ///< per-agent dt, 0 skips (empty: the step's dt)
  std::span<const std::uint8_t> steer;  ///< 0: goal only, no neighbours (with dt)
};

class PlanarFlock {
 public:
  /// Builds the kernels on runtime, else the process's default device; throws NoDeviceError
  /// without one, std::invalid_argument for a radius that is not positive and finite.
  explicit PlanarFlock(const PlanarFlockParams& params,
                       std::shared_ptr<ClRuntime> runtime = nullptr);
  ~PlanarFlock();
  PlanarFlock(PlanarFlock&&) noexcept;
  PlanarFlock& operator=(PlanarFlock&&) noexcept;

  /// Steps the owned agents by dt (or controls.dt) seeing the ghosts, in place: one pass on
  /// the host (cells, counting sort, float conversion), four or five writes, one launch, one
  /// read-back of velocities; positions move by the new velocity in double on the host. Throws
  /// std::invalid_argument when lengths differ.
  void step(std::span<const std::uint64_t> ids, std::span<Vec2d> pos, std::span<Vec2d> vel,
            const PlanarAgents& ghosts, double dt, const PlanarControls& controls = {});

  /// The settings in use.
  const PlanarFlockParams& params() const;
  /// The device that steps the flock.
  std::string deviceDescription() const;

 private:
  struct Device;
  std::unique_ptr<Device> device_;
};

}  // namespace zonesim::gpu
