#pragma once
// Batch integration of many crowd agents (the semi-implicit Euler step toward each agent's
// desired velocity, with bounded acceleration), either by the double-precision CPU reference or
// on an OpenCL device in float. No OpenCL or Eigen header comes with it.

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "gpu/backend.h"
#include "gpu/particle_types.h"

namespace zonesim::gpu {

class ClRuntime;
class ClCrowd;

class CrowdBatch {
 public:
  /// OpenCl uses runtime, else the process's default device; throws NoDeviceError without one.
  explicit CrowdBatch(Backend backend, std::shared_ptr<ClRuntime> runtime = nullptr);
  ~CrowdBatch();
  CrowdBatch(CrowdBatch&&) noexcept;
  CrowdBatch& operator=(CrowdBatch&&) noexcept;

  /// Replaces every agent (one upload on OpenCl); the spans must have the same length.
  void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities);
  /// One step for every agent: dv = desired - v clamped to max_acceleration * dt in length,
  /// v += dv, x += v dt. desired has one entry per agent (one upload on OpenCl). Throws
  /// std::invalid_argument unless dt > 0 and max_acceleration >= 0, both finite.
  void step(std::span<const Vec3d> desired, double dt, double max_acceleration);

  /// Agents in the batch.
  std::size_t size() const { return size_; }
  /// Copies the positions into out (one read-back on OpenCl).
  void readPositions(std::vector<Vec3d>& out) const;
  /// Copies the velocities into out (one read-back on OpenCl).
  void readVelocities(std::vector<Vec3d>& out) const;
  /// The backend chosen at construction.
  Backend backend() const { return backend_; }
  /// The device that integrates.
  std::string deviceDescription() const;

 private:
  Backend backend_;
  std::size_t size_ = 0;
  // The CPU backend's state; empty on OpenCl.
  std::vector<Vec3d> x_, v_;
  std::unique_ptr<ClCrowd> device_;
};

}  // namespace zonesim::gpu
