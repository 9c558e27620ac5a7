#pragma once
// The OpenCL crowd batch: float4 positions and velocities stay on the device; a step is one
// write of the desired velocities and one launch. Internal to gpu/.

#include <memory>
#include <span>
#include <vector>

#include "gpu/cl_runtime.h"
#include "gpu/crowd_engine.h"

namespace zonesim::gpu {

class ClCrowd final : public CrowdEngine {
 public:
  /// Builds the kernel on runtime's device; throws GpuError on failure.
  explicit ClCrowd(std::shared_ptr<const ClRuntime> runtime);
  /// Waits for queued commands, since a pending upload still reads host memory.
  ~ClCrowd() override;
  ClCrowd(const ClCrowd&) = delete;
  ClCrowd& operator=(const ClCrowd&) = delete;

  /// Uploads the agents (two writes); buffers grow only past their capacity.
  void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) override;
  /// Uploads desired (one write) and queues the step.
  void step(std::span<const Vec3d> desired, double dt, double max_dv) override;
  /// Positions of every agent (one blocking read).
  void readPositions(std::vector<Vec3d>& out) override;
  /// Velocities of every agent (one blocking read).
  void readVelocities(std::vector<Vec3d>& out) override;
  /// The device's description.
  std::string description() const override { return runtime_->description(); }

 private:
  void write(cl_mem buffer, std::span<const Vec3d> values);
  void read(cl_mem buffer, std::vector<Vec3d>& out);

  std::shared_ptr<const ClRuntime> runtime_;
  ClProgram program_;
  ClKernel integrate_;
  std::size_t count_ = 0;
  std::size_t capacity_ = 0;
  ClBuffer pos_;
  ClBuffer vel_;
  ClBuffer desired_;
  std::vector<cl_float4> host_;
};

}  // namespace zonesim::gpu
