#include "gpu/cl_particles.h"

#include <algorithm>
#include <utility>

#include "gpu/cl_error.h"

namespace zonesim::gpu {
namespace {

static_assert(sizeof(ClParticles::EmitRecord) == 32, "must match EmitRecord in particles.cl");
// Every state field (float components, uint life) is one 4-byte word per slot.
static_assert(sizeof(cl_uint) == sizeof(cl_float));
constexpr std::size_t kWordBytes = sizeof(cl_float);

}  // namespace

ClParticles::ClParticles(std::shared_ptr<const ClRuntime> runtime)
    : runtime_(std::move(runtime)),
      program_(runtime_->buildEmbeddedProgram("particles")),
      integrate_(program_.createKernel("integrate_particles")),
      scatter_(program_.createKernel("scatter_emitted")) {
  sphere_capacity_ = 1;
  spheres_ = runtime_->createBuffer(sizeof(cl_float4), CL_MEM_READ_ONLY);
  integrate_.setArg(15, spheres_.get());
}

ClParticles::~ClParticles() {
  // No throwing from a destructor: a failed finish has nothing left to protect.
  clFinish(runtime_->queue());
}

void ClParticles::reserve(std::size_t slots) {
  if (slots > capacity_) grow(slots);
}

void ClParticles::grow(std::size_t slots) {
  std::size_t capacity = std::max({slots, 2 * capacity_, std::size_t(1024)});
  for (int f = 0; f < FieldCount; ++f) {
    ClBuffer bigger = runtime_->createBuffer(capacity * kWordBytes);
    if (used_ > 0) {
      // Device to device, queued before any later launch: the host never sees the state.
      checkCl(clEnqueueCopyBuffer(runtime_->queue(), state_[f].get(), bigger.get(), 0, 0,
                                  used_ * kWordBytes, 0, nullptr, nullptr),
              "clEnqueueCopyBuffer");
    }
    state_[f] = std::move(bigger);
    cl_mem mem = state_[f].get();
    integrate_.setArg(cl_uint(f), mem);
    scatter_.setArg(cl_uint(2 + f), mem);
  }
  capacity_ = capacity;
}

void ClParticles::waitForUpload() {
  if (!staging_write_) return;
  cl_event event = staging_write_.get();
  checkCl(clWaitForEvents(1, &event), "clWaitForEvents");
  staging_write_.reset();
}

void ClParticles::upload(std::span<const NewParticle> batch, std::size_t slot_count) {
  if (slot_count > capacity_) grow(slot_count);
  used_ = std::max(used_, slot_count);
  if (batch.empty()) return;

  waitForUpload();
  staging_host_.resize(batch.size());
  for (std::size_t i = 0; i < batch.size(); ++i) {
    const NewParticle& p = batch[i];
    staging_host_[i] = {p.slot,
                        p.life_us,
                        cl_float(p.position.x),
                        cl_float(p.position.y),
                        cl_float(p.position.z),
                        cl_float(p.velocity.x),
                        cl_float(p.velocity.y),
                        cl_float(p.velocity.z)};
  }
  if (batch.size() > staging_capacity_) {
    staging_capacity_ = std::max(batch.size(), 2 * staging_capacity_);
    staging_ = runtime_->createBuffer(staging_capacity_ * sizeof(EmitRecord), CL_MEM_READ_ONLY);
    scatter_.setArg(0, staging_.get());
  }
  std::size_t bytes = batch.size() * sizeof(EmitRecord);
  cl_event written = nullptr;
  checkCl(clEnqueueWriteBuffer(runtime_->queue(), staging_.get(), CL_FALSE, 0, bytes,
                               staging_host_.data(), 0, nullptr, &written),
          "clEnqueueWriteBuffer");
  staging_write_.reset(written);
  scatter_.setArg(1, cl_uint(batch.size()));
  scatter_.enqueue(runtime_->queue(), batch.size());
  ++stats_.writes;
  stats_.bytes_written += bytes;
  ++stats_.launches;
}

void ClParticles::uploadSpheres(std::span<const Sphere> spheres) {
  bool same = spheres.size() == spheres_host_.size();
  for (std::size_t k = 0; same && k < spheres.size(); ++k) {
    const cl_float4& h = spheres_host_[k];
    const Sphere& s = spheres[k];
    same = h.s[0] == cl_float(s.center.x) && h.s[1] == cl_float(s.center.y) &&
           h.s[2] == cl_float(s.center.z) && h.s[3] == cl_float(s.radius);
  }
  if (same) return;
  spheres_host_.resize(spheres.size());
  for (std::size_t k = 0; k < spheres.size(); ++k) {
    const Sphere& s = spheres[k];
    spheres_host_[k] = {
        {cl_float(s.center.x), cl_float(s.center.y), cl_float(s.center.z), cl_float(s.radius)}};
  }
  if (spheres.size() > sphere_capacity_) {
    sphere_capacity_ = spheres.size();
    spheres_ = runtime_->createBuffer(sphere_capacity_ * sizeof(cl_float4), CL_MEM_READ_ONLY);
    integrate_.setArg(15, spheres_.get());
  }
  if (spheres.empty()) return;
  std::size_t bytes = spheres.size() * sizeof(cl_float4);
  // Blocking: the list is small and spheres_host_ may change on the next step.
  checkCl(clEnqueueWriteBuffer(runtime_->queue(), spheres_.get(), CL_TRUE, 0, bytes,
                               spheres_host_.data(), 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
  ++stats_.writes;
  stats_.bytes_written += bytes;
}

void ClParticles::step(const StepParams& params, std::size_t slot_count) {
  if (slot_count == 0) return;
  uploadSpheres(params.spheres);
  integrate_.setArg(16, cl_uint(params.spheres.size()));
  integrate_.setArg(7, cl_uint(slot_count));
  integrate_.setArg(8, cl_float(params.dt));
  integrate_.setArg(9, cl_uint(params.dt_us));
  integrate_.setArg(10, cl_float(params.gravity.x));
  integrate_.setArg(11, cl_float(params.gravity.y));
  integrate_.setArg(12, cl_float(params.gravity.z));
  integrate_.setArg(13, cl_float(params.drag));
  integrate_.setArg(14, cl_float(params.restitution));
  integrate_.enqueue(runtime_->queue(), slot_count);
  ++stats_.launches;
}

void ClParticles::read3(std::size_t slot_count, Field first, std::vector<Vec3d>& out) {
  out.resize(slot_count);
  if (slot_count == 0) return;
  read_scratch_.resize(3 * slot_count);
  std::size_t bytes = slot_count * sizeof(cl_float);
  for (int c = 0; c < 3; ++c) {
    // Only the last read blocks: the queue is in order, so the earlier ones are done by then.
    checkCl(
        clEnqueueReadBuffer(runtime_->queue(), state_[first + c].get(), c == 2 ? CL_TRUE : CL_FALSE,
                            0, bytes, read_scratch_.data() + c * slot_count, 0, nullptr, nullptr),
        "clEnqueueReadBuffer");
  }
  stats_.reads += 3;
  stats_.bytes_read += 3 * bytes;
  const cl_float* x = read_scratch_.data();
  const cl_float* y = x + slot_count;
  const cl_float* z = y + slot_count;
  for (std::size_t i = 0; i < slot_count; ++i) out[i] = {x[i], y[i], z[i]};
}

void ClParticles::readPositions(std::size_t slot_count, std::vector<Vec3d>& out) {
  read3(slot_count, Px, out);
}

void ClParticles::readVelocities(std::size_t slot_count, std::vector<Vec3d>& out) {
  read3(slot_count, Vx, out);
}

}  // namespace zonesim::gpu
