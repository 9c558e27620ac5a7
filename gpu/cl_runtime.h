#pragma once
// One OpenCL device with its context and in-order queue, chosen once: the first GPU on any
// platform, else the first CPU device (PoCL here). Internal to gpu/ and its tests; zone_node
// reaches it only through ParticleSystem.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gpu/cl_handles.h"
#include "gpu/cl_program.h"
#include "gpu/particle_types.h"

namespace zonesim::gpu {

/// Which device to open.
enum class DeviceType {
  GpuThenCpu,  ///< The first GPU on any platform, else the first CPU device.
  Gpu,
  Cpu,
  Accelerator,
};

/// "gpu-then-cpu", "gpu", "cpu" or "accelerator".
const char* deviceTypeName(DeviceType type);

class ClRuntime {
 public:
  /// Opens a device of the given type; throws NoDeviceError when there is none.
  explicit ClRuntime(DeviceType type = DeviceType::GpuThenCpu);

  /// "platform / device (GPU|CPU|accelerator, OpenCL C x.y)", for logs and reports.
  const std::string& description() const { return description_; }
  /// True when the chosen device is a GPU (data crosses a bus, so transfers cost more).
  bool isGpu() const { return is_gpu_; }

  /// Builds source for this device; on failure throws GpuError whose text holds the build log.
  ClProgram buildProgram(std::string_view name, std::string_view source,
                         const std::string& options = "") const;
  /// Builds one of the kernels embedded from gpu/kernels/ (name is the file stem).
  ClProgram buildEmbeddedProgram(std::string_view name) const;
  /// Allocates a device buffer of bytes bytes; throws CL_INVALID_BUFFER_SIZE for 0.
  ClBuffer createBuffer(std::size_t bytes, cl_mem_flags flags = CL_MEM_READ_WRITE) const;
  /// Blocks until everything queued so far has run.
  void finish() const;
  /// Reads count float4 vectors (x, y, z used) from buffer into out, through staging; blocks.
  void readFloat4s(cl_mem buffer, std::size_t count, std::vector<cl_float4>& staging,
                   std::vector<Vec3d>& out) const;

  /// The context, for calls this class does not wrap.
  cl_context context() const { return context_.get(); }
  /// The in-order queue that every command of this runtime goes through.
  cl_command_queue queue() const { return queue_.get(); }
  /// The device.
  cl_device_id device() const { return device_; }

  /// How many devices of the type exist on all platforms (0 when there is no platform).
  static std::size_t countDevices(DeviceType type);

 private:
  cl_device_id device_ = nullptr;
  bool is_gpu_ = false;
  std::string description_;
  ClContext context_;
  ClQueue queue_;
};

}  // namespace zonesim::gpu
