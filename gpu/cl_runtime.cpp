#include "gpu/cl_runtime.h"

#include <vector>

#include "gpu/cl_error.h"
#include "gpu/kernel_sources.h"

namespace zonesim::gpu {
namespace {

// From cl_khr_icd: what the ICD loader returns when no vendor is installed.
constexpr cl_int kPlatformNotFoundKhr = -1001;

std::vector<cl_platform_id> listPlatforms() {
  cl_uint count = 0;
  cl_int status = clGetPlatformIDs(0, nullptr, &count);
  if (status == kPlatformNotFoundKhr || (status == CL_SUCCESS && count == 0)) {
    throw NoDeviceError("no OpenCL device: no OpenCL platform is installed (clGetPlatformIDs: " +
                            std::string(clErrorName(kPlatformNotFoundKhr)) +
                            "); install an ICD such as pocl-opencl-icd or a GPU driver",
                        kPlatformNotFoundKhr);
  }
  checkCl(status, "clGetPlatformIDs");
  std::vector<cl_platform_id> platforms(count);
  checkCl(clGetPlatformIDs(count, platforms.data(), nullptr), "clGetPlatformIDs");
  return platforms;
}

// CL_DEVICE_NOT_FOUND is an answer here, not an error: the platform simply has none.
std::vector<cl_device_id> listDevices(cl_platform_id platform, cl_device_type type) {
  cl_uint count = 0;
  cl_int status = clGetDeviceIDs(platform, type, 0, nullptr, &count);
  if (status == CL_DEVICE_NOT_FOUND) return {};
  checkCl(status, "clGetDeviceIDs");
  std::vector<cl_device_id> devices(count);
  checkCl(clGetDeviceIDs(platform, type, count, devices.data(), nullptr), "clGetDeviceIDs");
  return devices;
}

cl_device_type clTypeOf(DeviceType type) {
  switch (type) {
    case DeviceType::Gpu:
      return CL_DEVICE_TYPE_GPU;
    case DeviceType::Cpu:
      return CL_DEVICE_TYPE_CPU;
    case DeviceType::Accelerator:
      return CL_DEVICE_TYPE_ACCELERATOR;
    case DeviceType::GpuThenCpu:
      break;
  }
  return CL_DEVICE_TYPE_GPU | CL_DEVICE_TYPE_CPU;
}

std::string deviceString(cl_device_id device, cl_device_info what) {
  std::size_t size = 0;
  checkCl(clGetDeviceInfo(device, what, 0, nullptr, &size), "clGetDeviceInfo");
  std::string text(size, '\0');
  checkCl(clGetDeviceInfo(device, what, size, text.data(), nullptr), "clGetDeviceInfo");
  while (!text.empty() && text.back() == '\0') text.pop_back();
  return text;
}

std::string platformName(cl_platform_id platform) {
  std::size_t size = 0;
  checkCl(clGetPlatformInfo(platform, CL_PLATFORM_NAME, 0, nullptr, &size), "clGetPlatformInfo");
  std::string text(size, '\0');
  checkCl(clGetPlatformInfo(platform, CL_PLATFORM_NAME, size, text.data(), nullptr),
          "clGetPlatformInfo");
  while (!text.empty() && text.back() == '\0') text.pop_back();
  return text;
}

struct Choice {
  cl_platform_id platform = nullptr;
  cl_device_id device = nullptr;
};

Choice firstDevice(const std::vector<cl_platform_id>& platforms, cl_device_type type) {
  for (cl_platform_id platform : platforms) {
    std::vector<cl_device_id> devices = listDevices(platform, type);
    if (!devices.empty()) return {platform, devices.front()};
  }
  return {};
}

Choice chooseDevice(DeviceType type) {
  std::vector<cl_platform_id> platforms = listPlatforms();
  Choice choice;
  if (type == DeviceType::GpuThenCpu) {
    choice = firstDevice(platforms, CL_DEVICE_TYPE_GPU);
    if (!choice.device) choice = firstDevice(platforms, CL_DEVICE_TYPE_CPU);
  } else {
    choice = firstDevice(platforms, clTypeOf(type));
  }
  if (!choice.device) {
    throw NoDeviceError("no OpenCL device of type " + std::string(deviceTypeName(type)) + " on " +
                            std::to_string(platforms.size()) +
                            " platform(s) (clGetDeviceIDs: CL_DEVICE_NOT_FOUND)",
                        CL_DEVICE_NOT_FOUND);
  }
  return choice;
}

const char* typeLabel(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "GPU";
  if (type & CL_DEVICE_TYPE_CPU) return "CPU";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

}  // namespace

const char* deviceTypeName(DeviceType type) {
  switch (type) {
    case DeviceType::GpuThenCpu:
      return "gpu-then-cpu";
    case DeviceType::Gpu:
      return "gpu";
    case DeviceType::Cpu:
      return "cpu";
    case DeviceType::Accelerator:
      return "accelerator";
  }
  return "unknown";
}

ClRuntime::ClRuntime(DeviceType type) {
  Choice choice = chooseDevice(type);
  device_ = choice.device;
  cl_device_type cl_type = 0;
  checkCl(clGetDeviceInfo(device_, CL_DEVICE_TYPE, sizeof(cl_type), &cl_type, nullptr),
          "clGetDeviceInfo(CL_DEVICE_TYPE)");
  is_gpu_ = (cl_type & CL_DEVICE_TYPE_GPU) != 0;
  description_ = platformName(choice.platform) + " / " + deviceString(device_, CL_DEVICE_NAME) +
                 " (" + typeLabel(cl_type) + ", " +
                 deviceString(device_, CL_DEVICE_OPENCL_C_VERSION) + ")";

  const cl_context_properties properties[] = {
      CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(choice.platform), 0};
  cl_int status = CL_SUCCESS;
  context_.reset(clCreateContext(properties, 1, &device_, nullptr, nullptr, &status));
  checkCl(status, "clCreateContext");
  // In order, no profiling: commands run in the order the particle system relies on.
  queue_.reset(clCreateCommandQueue(context_.get(), device_, 0, &status));
  checkCl(status, "clCreateCommandQueue");
}

ClProgram ClRuntime::buildProgram(std::string_view name, std::string_view source,
                                  const std::string& options) const {
  const char* text = source.data();
  std::size_t length = source.size();
  cl_int status = CL_SUCCESS;
  ClProgramHandle program(clCreateProgramWithSource(context_.get(), 1, &text, &length, &status));
  checkCl(status, "clCreateProgramWithSource");

  status = clBuildProgram(program.get(), 1, &device_, options.c_str(), nullptr, nullptr);
  if (status != CL_SUCCESS) {
    std::string log;
    std::size_t size = 0;
    if (clGetProgramBuildInfo(program.get(), device_, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) ==
        CL_SUCCESS) {
      log.resize(size);
      clGetProgramBuildInfo(program.get(), device_, CL_PROGRAM_BUILD_LOG, size, log.data(),
                            nullptr);
      while (!log.empty() && log.back() == '\0') log.pop_back();
    }
    throw GpuError("clBuildProgram failed: " + std::string(clErrorName(status)) + " (" +
                       std::to_string(status) + ") building '" + std::string(name) + "' for " +
                       description_ + "; build log:\n" + (log.empty() ? "(empty)" : log),
                   status);
  }
  return ClProgram(std::move(program), std::string(name));
}

ClProgram ClRuntime::buildEmbeddedProgram(std::string_view name) const {
  return buildProgram(name, kernelSource(name));
}

ClBuffer ClRuntime::createBuffer(std::size_t bytes, cl_mem_flags flags) const {
  cl_int status = CL_SUCCESS;
  ClBuffer buffer(clCreateBuffer(context_.get(), flags, bytes, nullptr, &status));
  checkCl(status, "clCreateBuffer");
  return buffer;
}

void ClRuntime::finish() const {
  checkCl(clFinish(queue_.get()), "clFinish");
}

void ClRuntime::readFloat4s(cl_mem buffer, std::size_t count, std::vector<cl_float4>& staging,
                            std::vector<Vec3d>& out) const {
  out.resize(count);
  if (count == 0) return;
  staging.resize(count);
  checkCl(clEnqueueReadBuffer(queue(), buffer, CL_TRUE, 0, count * sizeof(cl_float4),
                              staging.data(), 0, nullptr, nullptr),
          "clEnqueueReadBuffer");
  for (std::size_t i = 0; i < count; ++i)
    out[i] = {staging[i].s[0], staging[i].s[1], staging[i].s[2]};
}

std::size_t ClRuntime::countDevices(DeviceType type) {
  std::vector<cl_platform_id> platforms;
  try {
    platforms = listPlatforms();
  } catch (const NoDeviceError&) {
    return 0;
  }
  std::size_t count = 0;
  for (cl_platform_id platform : platforms) count += listDevices(platform, clTypeOf(type)).size();
  return count;
}

}  // namespace zonesim::gpu
