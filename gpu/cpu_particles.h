#pragma once
// The CPU backend: the same scheme as gpu/kernels/particles.cl in double precision. It is the
// reference the OpenCL path is tested against, and the faster choice for small counts.

#include <cstdint>
#include <vector>

#include "gpu/particle_engine.h"

namespace zonesim::gpu {

class CpuParticles final : public ParticleEngine {
 public:
  void reserve(std::size_t slots) override;
  void upload(std::span<const NewParticle> batch, std::size_t slot_count) override;
  void step(const StepParams& params, std::size_t slot_count) override;
  void readPositions(std::size_t slot_count, std::vector<Vec3d>& out) override;
  void readVelocities(std::size_t slot_count, std::vector<Vec3d>& out) override;
  std::size_t capacity() const override { return px_.size(); }
  std::string description() const override { return "CPU reference (double precision)"; }
  TransferStats transfers() const override { return {}; }

 private:
  void grow(std::size_t slots);

  std::vector<double> px_, py_, pz_;
  std::vector<double> vx_, vy_, vz_;
  std::vector<std::uint32_t> life_us_;
};

}  // namespace zonesim::gpu
