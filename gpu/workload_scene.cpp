#include "gpu/workload_scene.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/rng.h"
#include "gpu/cl_runtime.h"
#include "gpu/default_runtime.h"

namespace zonesim::gpu {

WorkloadScene::WorkloadScene(Workload workload, Backend backend, std::size_t n,
                             std::shared_ptr<ClRuntime> runtime)
    : workload_(workload), runtime_(std::move(runtime)) {
  if (backend == Backend::OpenCl && !runtime_) runtime_ = defaultRuntime();
  std::shared_ptr<ClRuntime> device = backend == Backend::OpenCl ? runtime_ : nullptr;
  Pcg32 rng(n, 77);
  if (workload == Workload::Particles) {
    particles_ = std::make_unique<ParticleSystem>(backend, std::max<std::size_t>(n, 1), device);
    particles_->reserve(n);
    spheres_ = {{{0, 1, 0}, 1.5}, {{4, 0.5, 2}, 1.0}};
    for (int e = 0; e < 10; ++e) {
      std::size_t count = n / 10 + (std::size_t(e) < n % 10 ? 1 : 0);
      EmitSpec spec{{-5.0 + e, 4.0, -2.0 + 0.4 * e}, {0.1 * (e - 5), 1, 0}, 0.9, 5.0 + e, 600.0};
      particles_->emit(spec, count, rng);
    }
    return;
  }
  std::vector<Vec3d> x(n), v(n);
  if (workload == Workload::Boids) {
    const double side = std::cbrt(double(std::max<std::size_t>(n, 1)) / 0.5);
    BoidParams params;
    params.min_speed = 1.0;
    params.max_speed = 4.0;
    flock_ = std::make_unique<Flock>(backend, FlockBounds{{0, 0, 0}, {side, side, side}}, params,
                                     device);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = {rng.uniform(0, side), rng.uniform(0, side), rng.uniform(0, side)};
      v[i] = {rng.uniform(-2, 2), rng.uniform(-1, 1), rng.uniform(-2, 2)};
    }
    flock_->setAgents(x, v);
    return;
  }
  crowd_ = std::make_unique<CrowdBatch>(backend, device);
  const double side = std::sqrt(double(std::max<std::size_t>(n, 1)));
  desired_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = {rng.uniform(0, side), 0, rng.uniform(0, side)};
    v[i] = {rng.uniform(-1, 1), 0, rng.uniform(-1, 1)};
    desired_[i] = {rng.uniform(-3, 3), 0, rng.uniform(-3, 3)};
  }
  crowd_->setAgents(x, v);
}

WorkloadScene::~WorkloadScene() = default;

void WorkloadScene::step() {
  if (particles_) particles_->step(1.0 / 60.0, {0, -9.81, 0}, 0.1, 0.6, spheres_);
  if (flock_) flock_->step(1.0 / 30.0);
  if (crowd_) crowd_->step(desired_, 1.0 / 20.0, 4.0);
}

void WorkloadScene::finish() const {
  bool on_device = (particles_ && particles_->backend() == Backend::OpenCl) ||
                   (flock_ && flock_->backend() == Backend::OpenCl) ||
                   (crowd_ && crowd_->backend() == Backend::OpenCl);
  if (on_device) runtime_->finish();
}

void WorkloadScene::readPositions(std::vector<Vec3d>& out) const {
  if (particles_) particles_->readPositions(out);
  if (flock_) flock_->readPositions(out);
  if (crowd_) crowd_->readPositions(out);
}

double secondsPerTick(WorkloadScene& scene, int steps, int repeats) {
  std::vector<Vec3d> positions;
  auto tick = [&] {
    scene.step();
    if (scene.readEveryTick()) {
      scene.readPositions(positions);
    } else {
      scene.finish();
    }
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
