#include "gpu/cpu_particles.h"

#include <algorithm>

namespace zonesim::gpu {

void CpuParticles::reserve(std::size_t slots) {
  if (slots > capacity()) grow(slots);
}

void CpuParticles::grow(std::size_t slots) {
  // Doubling keeps growth rare when emitters ramp up without a reserve.
  std::size_t size = std::max(slots, 2 * capacity());
  for (auto* v : {&px_, &py_, &pz_, &vx_, &vy_, &vz_}) v->resize(size);
  life_us_.resize(size);
}

void CpuParticles::upload(std::span<const NewParticle> batch, std::size_t slot_count) {
  if (slot_count > capacity()) grow(slot_count);
  for (const NewParticle& p : batch) {
    px_[p.slot] = p.position.x;
    py_[p.slot] = p.position.y;
    pz_[p.slot] = p.position.z;
    vx_[p.slot] = p.velocity.x;
    vy_[p.slot] = p.velocity.y;
    vz_[p.slot] = p.velocity.z;
    life_us_[p.slot] = p.life_us;
  }
}

// Mirrors integrate_particles in gpu/kernels/particles.cl line for line; the scheme and why
// the bounce is resolved at the time of impact are explained there.
void CpuParticles::step(const StepParams& params, std::size_t slot_count) {
  const double dt = params.dt;
  const double gx = params.gravity.x, gy = params.gravity.y, gz = params.gravity.z;
  const double drag = params.drag, restitution = params.restitution;
  for (std::size_t i = 0; i < slot_count; ++i) {
    std::uint32_t remaining = life_us_[i];
    if (remaining == 0) continue;
    if (remaining <= params.dt_us) {
      life_us_[i] = 0;
      continue;
    }
    life_us_[i] = remaining - params.dt_us;

    double ux = vx_[i] + (gx - drag * vx_[i]) * dt;
    double uz = vz_[i] + (gz - drag * vz_[i]) * dt;
    px_[i] += ux * dt;
    pz_[i] += uz * dt;
    vx_[i] = ux;
    vz_[i] = uz;

    double y = py_[i];
    double v = vy_[i];
    double ay = gy - drag * v;
    double v1 = v + ay * dt;
    double y1 = y + v1 * dt;
    if (y1 >= 0.0) {
      py_[i] = y1;
      vy_[i] = v1;
      continue;
    }
    double f = y / (y - y1);
    double vc = std::min(v + ay * f * dt, 0.0);
    double rest = (1.0 - f) * dt;
    double out = -restitution * vc;
    out = std::max(out + (gy - drag * out) * rest, 0.0);
    py_[i] = out * rest;
    vy_[i] = out;
  }
}

void CpuParticles::readPositions(std::size_t slot_count, std::vector<Vec3d>& out) {
  out.resize(slot_count);
  for (std::size_t i = 0; i < slot_count; ++i) out[i] = {px_[i], py_[i], pz_[i]};
}

void CpuParticles::readVelocities(std::size_t slot_count, std::vector<Vec3d>& out) {
  out.resize(slot_count);
  for (std::size_t i = 0; i < slot_count; ++i) out[i] = {vx_[i], vy_[i], vz_[i]};
}

}  // namespace zonesim::gpu
