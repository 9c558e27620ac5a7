#include "gpu/cpu_particles.h"

#include <algorithm>
#include <cmath>

namespace zonesim::gpu {
namespace {

// Mirrors collide_spheres in gpu/kernels/particles.cl; the why is there.
void collideSpheres(Vec3d x0, Vec3d& x1, Vec3d& v, double dt, double restitution,
                    std::span<const Sphere> spheres) {
  Vec3d seg = x1 - x0;
  double a = dot(seg, seg);
  double best_t = 2.0;
  const Sphere* best = nullptr;
  for (const Sphere& s : spheres) {
    Vec3d d = x0 - s.center;
    double c0 = dot(d, d) - s.radius * s.radius;
    if (c0 < 0.0) {
      double len = std::sqrt(dot(d, d));
      Vec3d n = len > 0.0 ? d * (1.0 / len) : Vec3d{0, 1, 0};
      x1 = s.center + n * s.radius;
      double vn = dot(v, n);
      if (vn < 0.0) v = v - n * ((1.0 + restitution) * vn);
      x1.y = std::max(x1.y, 0.0);
      return;
    }
    double b = dot(d, seg);
    if (b >= 0.0 || a == 0.0) continue;
    double disc = b * b - a * c0;
    if (disc < 0.0) continue;
    double t = (-b - std::sqrt(disc)) / a;
    if (t <= 1.0 && t < best_t) {
      best_t = t;
      best = &s;
    }
  }
  if (best == nullptr) return;
  Vec3d p = x0 + seg * best_t;
  Vec3d n = (p - best->center) * (1.0 / best->radius);
  double vn = dot(v, n);
  if (vn < 0.0) v = v - n * ((1.0 + restitution) * vn);
  x1 = p + v * ((1.0 - best_t) * dt);
  x1.y = std::max(x1.y, 0.0);
}

}  // namespace

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

    Vec3d x0{px_[i], py_[i], pz_[i]};
    double ux = vx_[i] + (gx - drag * vx_[i]) * dt;
    double uz = vz_[i] + (gz - drag * vz_[i]) * dt;
    Vec3d x1{x0.x + ux * dt, 0.0, x0.z + uz * dt};
    Vec3d v1{ux, 0.0, uz};

    double y = x0.y;
    double v = vy_[i];
    double ay = gy - drag * v;
    v1.y = v + ay * dt;
    x1.y = y + v1.y * dt;
    if (x1.y < 0.0) {
      double f = y / (y - x1.y);
      double vc = std::min(v + ay * f * dt, 0.0);
      double rest = (1.0 - f) * dt;
      double out = -restitution * vc;
      out = std::max(out + (gy - drag * out) * rest, 0.0);
      x1.y = out * rest;
      v1.y = out;
    }
    if (!params.spheres.empty()) collideSpheres(x0, x1, v1, dt, restitution, params.spheres);
    px_[i] = x1.x;
    py_[i] = x1.y;
    pz_[i] = x1.z;
    vx_[i] = v1.x;
    vy_[i] = v1.y;
    vz_[i] = v1.z;
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
