#include "gpu/workload_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/rng.h"
#include "gpu/cl_runtime.h"
#include "gpu/default_runtime.h"

namespace zonesim::gpu {

ParticleWorkload::ParticleWorkload(Backend backend, std::size_t n,
                                   std::shared_ptr<ClRuntime> runtime)
    : runtime_(std::move(runtime)) {
  if (backend == Backend::OpenCl && !runtime_) runtime_ = defaultRuntime();
  std::shared_ptr<ClRuntime> device = backend == Backend::OpenCl ? runtime_ : nullptr;
  Pcg32 rng(n, 77);
  particles_ = std::make_unique<ParticleSystem>(backend, std::max<std::size_t>(n, 1), device);
  particles_->reserve(n);
  spheres_ = {{{0, 1, 0}, 1.5}, {{4, 0.5, 2}, 1.0}};
  for (int e = 0; e < 10; ++e) {
    std::size_t count = n / 10 + (std::size_t(e) < n % 10 ? 1 : 0);
    EmitSpec spec{{-5.0 + e, 4.0, -2.0 + 0.4 * e}, {0.1 * (e - 5), 1, 0}, 0.9, 5.0 + e, 600.0};
    particles_->emit(spec, count, rng);
  }
}

ParticleWorkload::~ParticleWorkload() = default;

void ParticleWorkload::step() {
  particles_->step(1.0 / 60.0, {0, -9.81, 0}, 0.1, 0.6, spheres_);
}

void ParticleWorkload::finish() const {
  if (particles_->backend() == Backend::OpenCl) runtime_->finish();
}

void ParticleWorkload::readPositions(std::vector<Vec3d>& out) const {
  particles_->readPositions(out);
}

double secondsPerTick(ParticleWorkload& scene, int steps, int repeats) {
  auto tick = [&] {
    scene.step();
    scene.finish();
  };
  tick();
  double best = INFINITY;
  for (int r = 0; r < repeats; ++r) {
    auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) tick();
    std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    best = std::min(best, elapsed.count() / steps);
  }
  return best;
}

}  // namespace zonesim::gpu
