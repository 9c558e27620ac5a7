#include "gpu/crowd_batch.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/cl_crowd.h"
#include "gpu/crowd_engine.h"
#include "gpu/default_runtime.h"

namespace zonesim::gpu {
namespace {

// The reference in double; mirrors integrate_crowd in gpu/kernels/crowd.cl.
class CpuCrowd final : public CrowdEngine {
 public:
  void setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) override {
    x_.assign(positions.begin(), positions.end());
    v_.assign(velocities.begin(), velocities.end());
  }
  void step(std::span<const Vec3d> desired, double dt, double max_dv) override {
    for (std::size_t i = 0; i < x_.size(); ++i) {
      Vec3d& v = v_[i];
      Vec3d dv{desired[i].x - v.x, desired[i].y - v.y, desired[i].z - v.z};
      double len = std::sqrt(dv.x * dv.x + dv.y * dv.y + dv.z * dv.z);
      if (len > max_dv) {
        double s = max_dv / len;
        dv = {dv.x * s, dv.y * s, dv.z * s};
      }
      v = {v.x + dv.x, v.y + dv.y, v.z + dv.z};
      x_[i] = {x_[i].x + v.x * dt, x_[i].y + v.y * dt, x_[i].z + v.z * dt};
    }
  }
  void readPositions(std::vector<Vec3d>& out) override { out = x_; }
  void readVelocities(std::vector<Vec3d>& out) override { out = v_; }
  std::string description() const override { return "CPU reference (double precision)"; }

 private:
  std::vector<Vec3d> x_, v_;
};

std::unique_ptr<CrowdEngine> makeEngine(Backend backend, std::shared_ptr<ClRuntime> runtime) {
  if (backend == Backend::Cpu) return std::make_unique<CpuCrowd>();
  return std::make_unique<ClCrowd>(runtime ? std::move(runtime) : defaultRuntime());
}

}  // namespace

CrowdBatch::CrowdBatch(Backend backend, std::shared_ptr<ClRuntime> runtime)
    : AgentBatch(backend, makeEngine(backend, std::move(runtime)), "crowd") {}

void CrowdBatch::step(std::span<const Vec3d> desired, double dt, double max_acceleration) {
  if (desired.size() != size()) {
    throw std::invalid_argument("crowd step needs one desired velocity per agent: " +
                                std::to_string(desired.size()) + " for " + std::to_string(size()));
  }
  if (!std::isfinite(dt) || !(dt > 0.0) || !std::isfinite(max_acceleration) ||
      !(max_acceleration >= 0.0)) {
    throw std::invalid_argument("crowd step needs dt > 0 and max_acceleration >= 0, finite");
  }
  // AgentBatch holds the CrowdEngine made above.
  static_cast<CrowdEngine&>(engine()).step(desired, dt, max_acceleration * dt);
}

}  // namespace zonesim::gpu
