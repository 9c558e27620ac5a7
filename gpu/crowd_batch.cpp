#include "gpu/crowd_batch.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "gpu/cl_crowd.h"
#include "gpu/default_runtime.h"

namespace zonesim::gpu {

CrowdBatch::CrowdBatch(Backend backend, std::shared_ptr<ClRuntime> runtime) : backend_(backend) {
  if (backend == Backend::OpenCl) {
    device_ = std::make_unique<ClCrowd>(runtime ? std::move(runtime) : defaultRuntime());
  }
}

CrowdBatch::~CrowdBatch() = default;
CrowdBatch::CrowdBatch(CrowdBatch&&) noexcept = default;
CrowdBatch& CrowdBatch::operator=(CrowdBatch&&) noexcept = default;

void CrowdBatch::setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) {
  if (positions.size() != velocities.size()) {
    throw std::invalid_argument("crowd positions and velocities differ in length");
  }
  size_ = positions.size();
  if (device_) {
    device_->setAgents(positions, velocities);
    return;
  }
  x_.assign(positions.begin(), positions.end());
  v_.assign(velocities.begin(), velocities.end());
}

// Mirrors integrate_crowd in gpu/kernels/crowd.cl.
void CrowdBatch::step(std::span<const Vec3d> desired, double dt, double max_acceleration) {
  if (desired.size() != size_) {
    throw std::invalid_argument("crowd step needs one desired velocity per agent: " +
                                std::to_string(desired.size()) + " for " + std::to_string(size_));
  }
  if (!std::isfinite(dt) || !(dt > 0.0) || !std::isfinite(max_acceleration) ||
      !(max_acceleration >= 0.0)) {
    throw std::invalid_argument("crowd step needs dt > 0 and max_acceleration >= 0, finite");
  }
  const double max_dv = max_acceleration * dt;
  if (device_) {
    device_->step(desired, dt, max_dv);
    return;
  }
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

void CrowdBatch::readPositions(std::vector<Vec3d>& out) const {
  if (device_) {
    device_->readPositions(out);
  } else {
    out = x_;
  }
}

void CrowdBatch::readVelocities(std::vector<Vec3d>& out) const {
  if (device_) {
    device_->readVelocities(out);
  } else {
    out = v_;
  }
}

std::string CrowdBatch::deviceDescription() const {
  return device_ ? device_->description() : "CPU reference (double precision)";
}

}  // namespace zonesim::gpu
