#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu::test {
namespace {

struct Probe {
  std::shared_ptr<ClRuntime> runtime;
  std::string reason;
};

const Probe& probe() {
  static const Probe result = [] {
    Probe p;
    try {
      p.runtime = std::make_shared<ClRuntime>();
    } catch (const NoDeviceError& e) {
      p.reason = e.what();
    }
    return p;
  }();
  return result;
}

}  // namespace

std::shared_ptr<ClRuntime> sharedRuntime() {
  return probe().runtime;
}

const std::string& noDeviceReason() {
  return probe().reason;
}

ParticleSystem makeSystem(Backend backend, std::size_t max_particles) {
  return ParticleSystem(backend, max_particles,
                        backend == Backend::OpenCl ? sharedRuntime() : nullptr);
}

}  // namespace zonesim::gpu::test
