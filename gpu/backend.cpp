#include "gpu/backend.h"

#include <stdexcept>
#include <string>

#include "gpu/cl_runtime.h"

namespace zonesim::gpu {

const char* backendName(Backend backend) {
  return backend == Backend::OpenCl ? "opencl" : "cpu";
}

GpuMode parseGpuMode(std::string_view text) {
  if (text == "off") return GpuMode::Off;
  if (text == "on") return GpuMode::On;
  if (text == "auto") return GpuMode::Auto;
  throw std::invalid_argument("--gpu must be on, off or auto, not '" + std::string(text) + "'");
}

Backend chooseBackend(GpuMode mode, bool offload_pays) {
  switch (mode) {
    case GpuMode::Off:
      return Backend::Cpu;
    case GpuMode::On:
      return Backend::OpenCl;
    case GpuMode::Auto:
      break;
  }
  return offload_pays ? Backend::OpenCl : Backend::Cpu;
}

Backend chooseBackend(GpuMode mode, std::size_t particles, bool opencl_available) {
  return chooseBackend(mode, opencl_available && particles >= kAutoGpuThreshold);
}

bool openClAvailable() {
  // A broken driver is treated like a missing one: auto must never stop a run.
  static const bool available = [] {
    try {
      return ClRuntime::countDevices(DeviceType::GpuThenCpu) > 0;
    } catch (const GpuError&) {
      return false;
    }
  }();
  return available;
}

Backend selectBackend(std::string_view mode, std::size_t particles) {
  GpuMode parsed = parseGpuMode(mode);
  // Only auto needs to probe the driver; on and off must not pay for it.
  bool available = parsed == GpuMode::Auto && openClAvailable();
  return chooseBackend(parsed, particles, available);
}

}  // namespace zonesim::gpu
