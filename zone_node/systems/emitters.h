#pragma once
// Particle emitters: each emitter entity spawns particles at its rate; the particles of all
// emitters that share drag and restitution are integrated as one batch (gravity, drag, ground
// bounce) on OpenCL when it pays, else on the CPU (gpu/). Particles are zone-local effects:
// they neither migrate nor get published; an emitter that leaves the zone leaves its particles
// to die out here.

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gpu/offload.h"
#include "zone_node/entity_store.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct EmitterPopulation;
}  // namespace zonesim

namespace zonesim::gpu {
class ParticleSystem;
}

namespace zonesim::zone {

class EmitterSystem : public ZoneSystem {
 public:
  /// gpu_mode is "on", "off" or "auto" (see gpu/backend.h); auto offloads from the particle
  /// threshold, which every rank must share (zone_node/cluster/offload_agreement.h).
  EmitterSystem(const std::vector<EmitterPopulation>& emitters, const std::string& gpu_mode,
                const gpu::OffloadThresholds& thresholds);
  ~EmitterSystem();

  /// Emitters may migrate in at any tick: the step itself returns at once without any.
  bool active() const override { return true; }
  /// Emits for every emitter in the store and integrates all particles; counts those alive.
  void step(StepContext& ctx) override;
  /// Position and velocity (x, y, z, vx, vy, vz) of every live particle, appended to out
  /// (reads back from the device on OpenCL).
  void liveParticles(std::vector<std::array<double, 6>>& out) const;
  /// "cpu", "opencl", or "none" when the scene has no emitters.
  std::string backendName() const;

 private:
  /// Returns the particles alive.
  std::uint64_t advance(EntityStore& store, double dt);

  using Medium = std::pair<double, double>;  // (drag, restitution) shared by a batch

  gpu::ParticleSystem& batchFor(const EmitterData& e);

  bool opencl_ = false;                     // decided once from the scene's particle budget
  std::map<Medium, std::size_t> capacity_;  // from the scene: every emitter that could come here
  std::map<Medium, std::unique_ptr<gpu::ParticleSystem>> batches_;
  std::string backend_ = "none";
};

}  // namespace zonesim::zone
