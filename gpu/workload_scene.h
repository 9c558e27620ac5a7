#pragma once
// Synthetic scenes of n items per workload, the same for the start-up probe (gpu/offload_probe.h)
// and bench/gpu, so that the thresholds and the published figures measure one thing.

#include <cstddef>
#include <memory>
#include <vector>

#include "gpu/backend.h"
#include "gpu/crowd_batch.h"
#include "gpu/flock.h"
#include "gpu/offload.h"
#include "gpu/particle_system.h"

namespace zonesim::gpu {

class ClRuntime;

class WorkloadScene {
 public:
  /// Builds n items of workload on backend (runtime: the device for OpenCl, else the default):
  /// particles: ten sprays over two spheres, long-lived; boids: a flock at 0.5 boids/m^3 in a
  /// cube (about 17 neighbours each); crowd: agents on a square with fixed desired velocities.
  WorkloadScene(Workload workload, Backend backend, std::size_t n,
                std::shared_ptr<ClRuntime> runtime = nullptr);
  ~WorkloadScene();
  WorkloadScene(const WorkloadScene&) = delete;
  WorkloadScene& operator=(const WorkloadScene&) = delete;

  /// Queues one step (particles 1/60 s, boids 1/30 s, crowd 1/20 s).
  void step();
  /// Waits until the device has run everything queued (nothing on the CPU backend).
  void finish() const;
  /// Positions of every item, in item order (one read-back on OpenCl).
  void readPositions(std::vector<Vec3d>& out) const;
  /// True when a zone needs the positions on the host every tick to publish them (boids and
  /// crowds), so a step's cost includes the read-back; particles are read only for metrics.
  bool readEveryTick() const { return workload_ != Workload::Particles; }

 private:
  Workload workload_;
  std::shared_ptr<ClRuntime> runtime_;
  std::unique_ptr<ParticleSystem> particles_;
  std::unique_ptr<Flock> flock_;
  std::unique_ptr<CrowdBatch> crowd_;
  std::vector<Vec3d> desired_;
  std::vector<Sphere> spheres_;
};

/// Seconds per tick (step, then finish or read-back as readEveryTick says): best of repeats
/// runs of steps ticks, after one warm-up tick.
double secondsPerTick(WorkloadScene& scene, int steps, int repeats);

}  // namespace zonesim::gpu
