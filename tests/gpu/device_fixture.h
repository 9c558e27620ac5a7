#pragma once
// The OpenCL device shared by the gpu tests; tests skip (not fail) where there is none.

#include <gtest/gtest.h>

#include <memory>
#include <ostream>
#include <string>

#include "gpu/backend.h"
#include "gpu/cl_runtime.h"
#include "gpu/particle_system.h"

namespace zonesim::gpu::test {

/// The default device opened once per process, or nullptr when there is none.
std::shared_ptr<ClRuntime> sharedRuntime();
/// Why sharedRuntime() is null (the NoDeviceError text), empty when it is not.
const std::string& noDeviceReason();
/// A ParticleSystem on backend, on the shared device for OpenCl.
ParticleSystem makeSystem(Backend backend, std::size_t max_particles = 1u << 20);

}  // namespace zonesim::gpu::test

namespace zonesim::gpu {

/// Lets gtest print "cpu"/"opencl" in parameterised test names instead of raw bytes.
inline void PrintTo(Backend backend, std::ostream* os) {
  *os << backendName(backend);
}

}  // namespace zonesim::gpu

/// Skips the current test when no OpenCL device exists, with the reason.
#define ZS_REQUIRE_OPENCL()                                                           \
  do {                                                                                \
    if (!::zonesim::gpu::test::sharedRuntime())                                       \
      GTEST_SKIP() << "no OpenCL device: " << ::zonesim::gpu::test::noDeviceReason(); \
  } while (0)

/// Skips when backend is OpenCl and no OpenCL device exists.
#define ZS_REQUIRE_BACKEND(backend)                                        \
  do {                                                                     \
    if ((backend) == ::zonesim::gpu::Backend::OpenCl) ZS_REQUIRE_OPENCL(); \
  } while (0)
