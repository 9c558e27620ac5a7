#pragma once
// Errors of the OpenCL layer, catchable without any OpenCL header: every failed call becomes
// one of these, with the call and the OpenCL error name in the message, never a wrong answer.

#include <stdexcept>
#include <string>

namespace zonesim::gpu {

/// An OpenCL call failed; what() names the call and the error (e.g. CL_INVALID_VALUE).
class GpuError : public std::runtime_error {
 public:
  /// message is the full text; code is the OpenCL status (0 when the failure had none).
  GpuError(const std::string& message, int code);
  /// The OpenCL status code, e.g. -30 for CL_INVALID_VALUE.
  int code() const { return code_; }

 private:
  int code_;
};

/// No OpenCL platform, or no device of the requested type: callers may fall back to the CPU.
class NoDeviceError : public GpuError {
 public:
  using GpuError::GpuError;
};

}  // namespace zonesim::gpu
