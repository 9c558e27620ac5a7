#pragma once
// The particle workload of n particles, the same for the start-up probe (gpu/offload_probe.h)
// and bench/gpu, so that the threshold and the published figures measure one thing.

#include <cstddef>
#include <memory>
#include <vector>

#include "gpu/backend.h"
#include "gpu/particle_system.h"

namespace zonesim::gpu {

class ClRuntime;

class ParticleWorkload {
 public:
  /// n particles on backend (runtime: the device for OpenCl, else the default): ten sprays over
  /// two spheres, long-lived.
  ParticleWorkload(Backend backend, std::size_t n, std::shared_ptr<ClRuntime> runtime = nullptr);
  ~ParticleWorkload();
  ParticleWorkload(const ParticleWorkload&) = delete;
  ParticleWorkload& operator=(const ParticleWorkload&) = delete;

  /// Queues one step of 1/60 s.
  void step();
  /// Waits until the device has run everything queued (nothing on the CPU backend).
  void finish() const;
  /// Positions of every particle, in slot order (one read-back on OpenCl).
  void readPositions(std::vector<Vec3d>& out) const;

 private:
  std::shared_ptr<ClRuntime> runtime_;
  std::unique_ptr<ParticleSystem> particles_;
  std::vector<Sphere> spheres_;
};

/// Seconds per tick (step, then finish: a zone reads particles only for metrics): best of
/// repeats runs of steps ticks, after one warm-up tick.
double secondsPerTick(ParticleWorkload& scene, int steps, int repeats);

}  // namespace zonesim::gpu
