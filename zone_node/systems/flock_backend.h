#pragma once
// Where one flocking population steps: the crowd library's double flock on the CPU, or the same
// rules in float on an OpenCL device (gpu/planar_flock.h) for flocks past the boids threshold.
// The choice depends only on the scene and on thresholds every rank shares
// (zone_node/cluster/offload_agreement.h), so all ranks of a cluster take the same backend.

#include <cstddef>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "crowd/flock.h"
#include "gpu/backend.h"
#include "gpu/offload.h"

namespace zonesim::gpu {
class PlanarFlock;
struct Vec2d;
}  // namespace zonesim::gpu

namespace zonesim::zone {

/// The backend for a flock of `agents` per zone (its count in the scene over the ranks, the
/// same on every rank): `gpu_mode` "off", "on" or "auto" as for particles (gpu/backend.h).
gpu::Backend flockBackendFor(std::string_view gpu_mode, std::size_t agents,
                             const gpu::OffloadThresholds& thresholds);

/// Times a zone flock step (agents at 0.3 per m^2, about 8 neighbours, a halo of ghosts) on the
/// crowd flock and on the OpenCL flock at each size: best of 2 runs of 3 steps after a warm-up
/// step, for gpu::crossover. Throws gpu::NoDeviceError without a device.
std::vector<gpu::ProbeSample> probeFlockBackends(std::span<const std::size_t> sizes);

/// One population's flock stepper on the chosen backend, with crowd::Flock's step signature.
class FlockBackend {
 public:
  /// Opens the device for OpenCl (gpu::NoDeviceError without one).
  FlockBackend(const crowd::FlockSettings& settings, gpu::Backend backend);
  ~FlockBackend();

  /// As crowd::Flock::step: advances `agents` by `dt`, seeing `ghosts`.
  void step(const crowd::AgentSpan& agents, const crowd::GhostSpan& ghosts, double dt,
            std::span<const crowd::Vec2> goal_vel = {}, const crowd::StepPlan& plan = {});
  /// The backend in use.
  gpu::Backend backend() const { return backend_; }

 private:
  gpu::Backend backend_;
  crowd::Flock cpu_;
  std::unique_ptr<gpu::PlanarFlock> device_;
  std::vector<gpu::Vec2d> pos_, vel_, ghost_pos_, ghost_vel_, goal_;  // conversions, kept warm
};

}  // namespace zonesim::zone
