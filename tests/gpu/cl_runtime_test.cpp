// The OpenCL layer's contract: a described device, embedded kernels, and every failure an
// exception that names the call and the OpenCL error (with the build log for a bad kernel).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "gpu/cl_error.h"
#include "gpu/kernel_sources.h"
#include "tests/gpu/device_fixture.h"

namespace zonesim::gpu {
namespace {

using test::sharedRuntime;
using ::testing::HasSubstr;

// Runs body, expects a GpuError, and returns its text and code for further checks.
template <typename Body>
GpuError expectGpuError(Body body) {
  try {
    body();
  } catch (const GpuError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a GpuError";
  return GpuError("none", 0);
}

TEST(ClErrorName, NamesKnownCodes) {
  EXPECT_STREQ(clErrorName(CL_INVALID_VALUE), "CL_INVALID_VALUE");
  EXPECT_STREQ(clErrorName(CL_BUILD_PROGRAM_FAILURE), "CL_BUILD_PROGRAM_FAILURE");
  EXPECT_STREQ(clErrorName(-1001), "CL_PLATFORM_NOT_FOUND_KHR");
  EXPECT_STREQ(clErrorName(-12345), "unknown OpenCL error");
}

TEST(CheckCl, ThrowsWithCallAndName) {
  GpuError e = expectGpuError([] { checkCl(CL_INVALID_VALUE, "clDoSomething"); });
  EXPECT_THAT(e.what(), HasSubstr("clDoSomething"));
  EXPECT_THAT(e.what(), HasSubstr("CL_INVALID_VALUE"));
  EXPECT_EQ(e.code(), CL_INVALID_VALUE);
  EXPECT_NO_THROW(checkCl(CL_SUCCESS, "clFine"));
}

TEST(EmbeddedKernels, CarryTheParticleKernels) {
  EXPECT_THAT(std::string(kernelSource("particles")),
              HasSubstr("__kernel void integrate_particles"));
  EXPECT_THROW(kernelSource("no_such_file"), std::out_of_range);
}

TEST(ClRuntime, DescribesTheChosenDevice) {
  ZS_REQUIRE_OPENCL();
  const std::string& text = sharedRuntime()->description();
  EXPECT_THAT(text, HasSubstr(" / "));
  EXPECT_THAT(text, HasSubstr(sharedRuntime()->isGpu() ? "(GPU" : "("));
  EXPECT_THAT(text, HasSubstr("OpenCL C"));
  // GPU first: when the machine has a GPU, the default runtime must be on it.
  if (ClRuntime::countDevices(DeviceType::Gpu) > 0) {
    EXPECT_TRUE(sharedRuntime()->isGpu());
  }
  RecordProperty("device", text);
}

TEST(ClRuntime, BuildsTheEmbeddedProgram) {
  ZS_REQUIRE_OPENCL();
  ClProgram program = sharedRuntime()->buildEmbeddedProgram("particles");
  EXPECT_NO_THROW(program.createKernel("integrate_particles"));
  EXPECT_NO_THROW(program.createKernel("scatter_emitted"));
}

TEST(ClRuntime, BadKernelSourceThrowsWithTheBuildLog) {
  ZS_REQUIRE_OPENCL();
  const char* broken =
      "__kernel void broken(__global float* x) { x[get_global_id(0)] = undefined_thing; }\n";
  GpuError e = expectGpuError([&] { sharedRuntime()->buildProgram("broken", broken); });
  EXPECT_EQ(e.code(), CL_BUILD_PROGRAM_FAILURE);
  EXPECT_THAT(e.what(), HasSubstr("clBuildProgram"));
  EXPECT_THAT(e.what(), HasSubstr("CL_BUILD_PROGRAM_FAILURE"));
  EXPECT_THAT(e.what(), HasSubstr("build log:"));
  // The compiler's own diagnostic, which names the offending identifier, is in the message.
  EXPECT_THAT(e.what(), HasSubstr("undefined_thing"));
}

TEST(ClRuntime, MissingDeviceTypeIsAClearNoDeviceError) {
  ZS_REQUIRE_OPENCL();
  if (ClRuntime::countDevices(DeviceType::Accelerator) > 0) {
    GTEST_SKIP() << "this machine has an OpenCL accelerator, so none is missing";
  }
  try {
    ClRuntime runtime(DeviceType::Accelerator);
    FAIL() << "expected NoDeviceError";
  } catch (const NoDeviceError& e) {
    EXPECT_EQ(e.code(), CL_DEVICE_NOT_FOUND);
    EXPECT_THAT(e.what(), HasSubstr("no OpenCL device of type accelerator"));
    EXPECT_THAT(e.what(), HasSubstr("CL_DEVICE_NOT_FOUND"));
  }
}

TEST(ClRuntime, ZeroSizedBufferNamesCallAndError) {
  ZS_REQUIRE_OPENCL();
  GpuError e = expectGpuError([] { sharedRuntime()->createBuffer(0); });
  EXPECT_EQ(e.code(), CL_INVALID_BUFFER_SIZE);
  EXPECT_THAT(e.what(), HasSubstr("clCreateBuffer"));
  EXPECT_THAT(e.what(), HasSubstr("CL_INVALID_BUFFER_SIZE"));
}

TEST(ClRuntime, UnknownKernelNameNamesCallAndError) {
  ZS_REQUIRE_OPENCL();
  ClProgram program = sharedRuntime()->buildEmbeddedProgram("particles");
  GpuError e = expectGpuError([&] { program.createKernel("no_such_kernel"); });
  EXPECT_EQ(e.code(), CL_INVALID_KERNEL_NAME);
  EXPECT_THAT(e.what(), HasSubstr("clCreateKernel(particles, no_such_kernel)"));
  EXPECT_THAT(e.what(), HasSubstr("CL_INVALID_KERNEL_NAME"));
}

TEST(ClRuntime, InvalidKernelArgumentsNameCallAndError) {
  ZS_REQUIRE_OPENCL();
  ClProgram program = sharedRuntime()->buildEmbeddedProgram("particles");
  ClKernel kernel = program.createKernel("integrate_particles");

  GpuError bad_index = expectGpuError([&] { kernel.setArg(99, cl_uint(1)); });
  EXPECT_EQ(bad_index.code(), CL_INVALID_ARG_INDEX);
  EXPECT_THAT(bad_index.what(), HasSubstr("clSetKernelArg(integrate_particles, arg 99)"));
  EXPECT_THAT(bad_index.what(), HasSubstr("CL_INVALID_ARG_INDEX"));

  // Argument 7 is the uint particle count: a one-byte value is the wrong size.
  const char one_byte = 1;
  GpuError bad_size = expectGpuError([&] { kernel.setArgBytes(7, 1, &one_byte); });
  EXPECT_EQ(bad_size.code(), CL_INVALID_ARG_SIZE);
  EXPECT_THAT(bad_size.what(), HasSubstr("CL_INVALID_ARG_SIZE"));
}

// Run by the ctest case gpu_tests.NoPlatform with the ICD loader pointed at an empty vendor
// directory; anywhere else it skips, since the loader reads that setting once per process.
TEST(NoPlatform, OpeningADeviceThrowsNoOpenClDevice) {
  if (std::getenv("ZONESIM_EXPECT_NO_OPENCL") == nullptr) {
    GTEST_SKIP() << "only meaningful under the gpu_tests.NoPlatform ctest case";
  }
  try {
    ClRuntime runtime;
    FAIL() << "expected NoDeviceError";
  } catch (const NoDeviceError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no OpenCL device"));
    EXPECT_THAT(e.what(), HasSubstr("CL_PLATFORM_NOT_FOUND_KHR"));
  }
  EXPECT_EQ(ClRuntime::countDevices(DeviceType::GpuThenCpu), 0u);
  EXPECT_FALSE(openClAvailable());
  EXPECT_EQ(selectBackend("auto", 100'000'000), Backend::Cpu);
  EXPECT_THROW(ParticleSystem(Backend::OpenCl), NoDeviceError);
  EXPECT_NO_THROW(ParticleSystem(Backend::Cpu));
}

}  // namespace
}  // namespace zonesim::gpu
