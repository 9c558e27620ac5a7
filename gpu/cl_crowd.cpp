#include "gpu/cl_crowd.h"

#include "gpu/cl_error.h"

namespace zonesim::gpu {

ClCrowd::ClCrowd(std::shared_ptr<const ClRuntime> runtime)
    : runtime_(std::move(runtime)),
      program_(runtime_->buildEmbeddedProgram("crowd")),
      integrate_(program_.createKernel("integrate_crowd")) {}

ClCrowd::~ClCrowd() {
  // No throwing from a destructor: a failed finish has nothing left to protect.
  clFinish(runtime_->queue());
}

void ClCrowd::write(cl_mem buffer, std::span<const Vec3d> values) {
  // Blocking: host_ is reused by the next write, and a tick's upload is one large copy.
  host_.resize(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    host_[i] = {{cl_float(values[i].x), cl_float(values[i].y), cl_float(values[i].z), 0.0f}};
  }
  checkCl(
      clEnqueueWriteBuffer(runtime_->queue(), buffer, CL_TRUE, 0, values.size() * sizeof(cl_float4),
                           host_.data(), 0, nullptr, nullptr),
      "clEnqueueWriteBuffer");
}

void ClCrowd::read(cl_mem buffer, std::vector<Vec3d>& out) {
  runtime_->readFloat4s(buffer, count_, host_, out);
}

void ClCrowd::setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) {
  count_ = positions.size();
  if (count_ == 0) return;
  if (count_ > capacity_) {
    capacity_ = count_;
    pos_ = runtime_->createBuffer(capacity_ * sizeof(cl_float4));
    vel_ = runtime_->createBuffer(capacity_ * sizeof(cl_float4));
    desired_ = runtime_->createBuffer(capacity_ * sizeof(cl_float4), CL_MEM_READ_ONLY);
    integrate_.setArg(0, pos_.get());
    integrate_.setArg(1, vel_.get());
    integrate_.setArg(2, desired_.get());
  }
  write(pos_.get(), positions);
  write(vel_.get(), velocities);
}

void ClCrowd::step(std::span<const Vec3d> desired, double dt, double max_dv) {
  if (count_ == 0) return;
  write(desired_.get(), desired);
  integrate_.setArg(3, cl_uint(count_));
  integrate_.setArg(4, cl_float(dt));
  integrate_.setArg(5, cl_float(max_dv));
  integrate_.enqueue(runtime_->queue(), count_);
}

void ClCrowd::readPositions(std::vector<Vec3d>& out) {
  read(pos_.get(), out);
}

void ClCrowd::readVelocities(std::vector<Vec3d>& out) {
  read(vel_.get(), out);
}

}  // namespace zonesim::gpu
