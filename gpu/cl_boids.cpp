#include "gpu/cl_boids.h"

#include <stdexcept>

#include "gpu/cl_error.h"

namespace zonesim::gpu {
namespace {

cl_float4 float4(double x, double y, double z, double w) {
  return {{cl_float(x), cl_float(y), cl_float(z), cl_float(w)}};
}

}  // namespace

ClBoids::ClBoids(std::shared_ptr<const ClRuntime> runtime, const GridSpec& grid,
                 const FlockBounds& bounds, const BoidParams& params)
    : runtime_(std::move(runtime)),
      grid_(grid),
      bounds_(bounds),
      params_(params),
      program_(runtime_->buildEmbeddedProgram("boids")),
      cells_(program_.createKernel("boid_cells")),
      bounds_kernel_(program_.createKernel("cell_bounds")),
      gather_(program_.createKernel("gather_boids")),
      step_(program_.createKernel("boid_step")),
      sort_(runtime_) {
  const std::size_t cells = grid_.cells();
  cell_start_ = runtime_->createBuffer(cells * sizeof(cl_uint));
  cell_end_ = runtime_->createBuffer(cells * sizeof(cl_uint));
  const cl_float4 grid4 = float4(grid_.origin.x, grid_.origin.y, grid_.origin.z, grid_.cell);
  cells_.setArg(3, grid4);
  bounds_kernel_.setArg(2, cell_start_.get());
  bounds_kernel_.setArg(3, cell_end_.get());
  step_.setArg(3, cell_start_.get());
  step_.setArg(4, cell_end_.get());
  step_.setArg(5, grid4);
  step_.setArg(7, float4(params_.separation_weight, params_.alignment_weight,
                         params_.cohesion_weight, params_.bounds_weight));
  step_.setArg(9, float4(bounds_.min.x, bounds_.min.y, bounds_.min.z, 0));
  step_.setArg(10, float4(bounds_.max.x, bounds_.max.y, bounds_.max.z, 0));
}

ClBoids::~ClBoids() {
  // No throwing from a destructor: a failed finish has nothing left to protect.
  clFinish(runtime_->queue());
}

void ClBoids::setAgents(std::span<const Vec3d> positions, std::span<const Vec3d> velocities) {
  if (positions.size() != velocities.size()) {
    throw std::invalid_argument("flock positions and velocities differ in length");
  }
  count_ = positions.size();
  clFinish(runtime_->queue());  // host_ may still be read by a previous upload
  if (count_ == 0) return;
  if (count_ > capacity_) {
    capacity_ = count_;
    padded_ = ClPairSort::paddedLength(count_);
    for (int b = 0; b < 2; ++b) {
      pos_[b] = runtime_->createBuffer(capacity_ * sizeof(cl_float4));
      vel_[b] = runtime_->createBuffer(capacity_ * sizeof(cl_float4));
    }
    pos_sorted_ = runtime_->createBuffer(capacity_ * sizeof(cl_float4));
    vel_sorted_ = runtime_->createBuffer(capacity_ * sizeof(cl_float4));
    keys_ = runtime_->createBuffer(padded_ * sizeof(cl_uint));
    vals_ = runtime_->createBuffer(padded_ * sizeof(cl_uint));
  }
  padded_ = ClPairSort::paddedLength(count_);
  current_ = 0;
  // One staging array for both fields: two large writes, no per-agent traffic.
  host_.resize(2 * count_);
  for (std::size_t i = 0; i < count_; ++i) {
    host_[i] = float4(positions[i].x, positions[i].y, positions[i].z, 0);
    host_[count_ + i] = float4(velocities[i].x, velocities[i].y, velocities[i].z, 0);
  }
  const std::size_t bytes = count_ * sizeof(cl_float4);
  checkCl(clEnqueueWriteBuffer(runtime_->queue(), pos_[0].get(), CL_FALSE, 0, bytes, host_.data(),
                               0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
  checkCl(clEnqueueWriteBuffer(runtime_->queue(), vel_[0].get(), CL_TRUE, 0, bytes,
                               host_.data() + count_, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
}

void ClBoids::enqueueGrid() {
  cl_command_queue queue = runtime_->queue();
  const cl_uint4 dims{{grid_.nx, grid_.ny, grid_.nz, cl_uint(count_)}};
  cells_.setArg(0, pos_[current_].get());
  cells_.setArg(1, keys_.get());
  cells_.setArg(2, vals_.get());
  cells_.setArg(4, dims);
  cells_.enqueue(queue, padded_);
  launches_ += 1 + sort_.enqueue(keys_.get(), vals_.get(), padded_);
  const cl_uint zero = 0;
  const std::size_t cell_bytes = grid_.cells() * sizeof(cl_uint);
  checkCl(clEnqueueFillBuffer(queue, cell_start_.get(), &zero, sizeof(zero), 0, cell_bytes, 0,
                              nullptr, nullptr),
          "clEnqueueFillBuffer");
  checkCl(clEnqueueFillBuffer(queue, cell_end_.get(), &zero, sizeof(zero), 0, cell_bytes, 0,
                              nullptr, nullptr),
          "clEnqueueFillBuffer");
  bounds_kernel_.setArg(0, keys_.get());
  bounds_kernel_.setArg(1, cl_uint(count_));
  bounds_kernel_.enqueue(queue, count_);
  ++launches_;
}

void ClBoids::step(double dt) {
  if (count_ == 0) return;
  enqueueGrid();
  const int next = 1 - current_;
  gather_.setArg(0, pos_[current_].get());
  gather_.setArg(1, vel_[current_].get());
  gather_.setArg(2, vals_.get());
  gather_.setArg(3, cl_uint(count_));
  gather_.setArg(4, pos_sorted_.get());
  gather_.setArg(5, vel_sorted_.get());
  gather_.enqueue(runtime_->queue(), count_);
  ++launches_;
  step_.setArg(0, pos_sorted_.get());
  step_.setArg(1, vel_sorted_.get());
  step_.setArg(2, vals_.get());
  step_.setArg(6, cl_uint4{{grid_.nx, grid_.ny, grid_.nz, cl_uint(count_)}});
  step_.setArg(8, float4(params_.perception_radius, params_.min_speed, params_.max_speed, dt));
  step_.setArg(11, pos_[next].get());
  step_.setArg(12, vel_[next].get());
  step_.enqueue(runtime_->queue(), count_);
  ++launches_;
  current_ = next;
}

void ClBoids::read4(cl_mem buffer, std::vector<Vec3d>& out) {
  runtime_->readFloat4s(buffer, count_, host_, out);
}

void ClBoids::readPositions(std::vector<Vec3d>& out) {
  read4(pos_[current_].get(), out);
}

void ClBoids::readVelocities(std::vector<Vec3d>& out) {
  read4(vel_[current_].get(), out);
}

void ClBoids::buildIndex(CellIndex& out) {
  out.order.resize(count_);
  out.cell_start.assign(grid_.cells(), 0);
  out.cell_end.assign(grid_.cells(), 0);
  if (count_ == 0) return;
  enqueueGrid();
  cl_command_queue queue = runtime_->queue();
  checkCl(clEnqueueReadBuffer(queue, vals_.get(), CL_FALSE, 0, count_ * sizeof(cl_uint),
                              out.order.data(), 0, nullptr, nullptr),
          "clEnqueueReadBuffer");
  checkCl(clEnqueueReadBuffer(queue, cell_start_.get(), CL_FALSE, 0,
                              out.cell_start.size() * sizeof(cl_uint), out.cell_start.data(), 0,
                              nullptr, nullptr),
          "clEnqueueReadBuffer");
  checkCl(
      clEnqueueReadBuffer(queue, cell_end_.get(), CL_TRUE, 0, out.cell_end.size() * sizeof(cl_uint),
                          out.cell_end.data(), 0, nullptr, nullptr),
      "clEnqueueReadBuffer");
}

}  // namespace zonesim::gpu
