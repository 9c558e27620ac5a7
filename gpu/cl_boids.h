#pragma once
// The OpenCL flock: float4 positions and velocities live on the device, double-buffered; each
// step builds the neighbour grid there (cell per boid, bitonic sort by cell, cell ranges) and
// steps every boid, with no host traffic. Internal to gpu/.

#include <array>
#include <memory>
#include <vector>

#include "gpu/boid_engine.h"
#include "gpu/cl_runtime.h"
#include "gpu/cl_sort.h"

namespace zonesim::gpu {

class ClBoids final : public BoidEngine {
 public:
  /// Builds the kernels on runtime's device; throws GpuError on failure.
  ClBoids(std::shared_ptr<const ClRuntime> runtime, const GridSpec& grid, const FlockBounds& bounds,
          const BoidParams& params);
  /// Waits for queued commands, since a pending upload still reads host memory.
  ~ClBoids() override;
  ClBoids(const ClBoids&) = delete;
  ClBoids& operator=(const ClBoids&) = delete;

  void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) override;
  void step(double dt) override;
  void readPositions(std::vector<Vec3d>& out) override;
  void readVelocities(std::vector<Vec3d>& out) override;
  void buildIndex(CellIndex& out) override;
  std::string description() const override { return runtime_->description(); }

  /// Kernel launches queued so far (the sort's included).
  std::size_t launches() const { return launches_; }

 private:
  void enqueueGrid();
  void read4(cl_mem buffer, std::vector<Vec3d>& out);

  std::shared_ptr<const ClRuntime> runtime_;
  GridSpec grid_;
  FlockBounds bounds_;
  BoidParams params_;
  ClProgram program_;
  ClKernel cells_;
  ClKernel bounds_kernel_;
  ClKernel gather_;
  ClKernel step_;
  ClPairSort sort_;
  std::size_t count_ = 0;
  std::size_t capacity_ = 0;
  std::size_t padded_ = 0;
  // The buffers holding the current state; 1 - current_ receives the next.
  int current_ = 0;
  std::array<ClBuffer, 2> pos_;
  std::array<ClBuffer, 2> vel_;
  // The current state in grid order, the step's input.
  ClBuffer pos_sorted_;
  ClBuffer vel_sorted_;
  ClBuffer keys_;
  ClBuffer vals_;
  ClBuffer cell_start_;
  ClBuffer cell_end_;
  std::vector<cl_float4> host_;
  std::size_t launches_ = 0;
};

}  // namespace zonesim::gpu
