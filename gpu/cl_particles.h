#pragma once
// The OpenCL backend: particle state lives on the device between steps in float SoA buffers.
// Traffic is one write per emit batch (scattered into recycled slots by a kernel), one launch
// per step and reads only when asked. Internal to gpu/.

#include <array>
#include <memory>
#include <vector>

#include "gpu/cl_runtime.h"
#include "gpu/particle_engine.h"

namespace zonesim::gpu {

class ClParticles final : public ParticleEngine {
 public:
  /// Builds the particle kernels on runtime's device; throws GpuError on any failure.
  explicit ClParticles(std::shared_ptr<const ClRuntime> runtime);
  /// Waits for queued commands, since a pending upload still reads host staging memory.
  ~ClParticles() override;
  ClParticles(const ClParticles&) = delete;
  ClParticles& operator=(const ClParticles&) = delete;

  void reserve(std::size_t slots) override;
  void upload(std::span<const NewParticle> batch, std::size_t slot_count) override;
  void step(const StepParams& params, std::size_t slot_count) override;
  void readPositions(std::size_t slot_count, std::vector<Vec3d>& out) override;
  void readVelocities(std::size_t slot_count, std::vector<Vec3d>& out) override;
  std::size_t capacity() const override { return capacity_; }
  std::string description() const override { return runtime_->description(); }
  TransferStats transfers() const override { return stats_; }

  /// The layout scatter_emitted reads; plain 4-byte fields, so host and device agree.
  struct EmitRecord {
    cl_uint slot;
    cl_uint life_us;
    cl_float px, py, pz;
    cl_float vx, vy, vz;
  };

 private:
  enum Field { Px, Py, Pz, Vx, Vy, Vz, Life, FieldCount };

  void grow(std::size_t slots);
  void read3(std::size_t slot_count, Field first, std::vector<Vec3d>& out);
  void waitForUpload();
  void uploadSpheres(std::span<const Sphere> spheres);

  std::shared_ptr<const ClRuntime> runtime_;
  ClProgram program_;
  ClKernel integrate_;
  ClKernel scatter_;
  std::array<ClBuffer, FieldCount> state_;
  std::size_t capacity_ = 0;
  // Slots holding data; growth copies only these, on the device.
  std::size_t used_ = 0;
  ClBuffer staging_;
  std::size_t staging_capacity_ = 0;
  std::vector<EmitRecord> staging_host_;
  // The non-blocking write still reading staging_host_; waited on before it is refilled.
  ClEvent staging_write_;
  std::vector<cl_float> read_scratch_;
  // Spheres as float4 (centre, radius); written only when the list changes, since it is static
  // in a scene. Never empty: OpenCL 1.2 has no zero-sized buffer to bind when there are none.
  ClBuffer spheres_;
  std::size_t sphere_capacity_ = 0;
  std::vector<cl_float4> spheres_host_;
  TransferStats stats_;
};

}  // namespace zonesim::gpu
