#pragma once
// Turning OpenCL status codes into exceptions that name the call and the error.

#include <string>

#include "gpu/cl_api.h"
#include "gpu/gpu_error.h"

namespace zonesim::gpu {

/// The symbolic name of an OpenCL status ("CL_INVALID_VALUE"), or "unknown OpenCL error".
const char* clErrorName(cl_int status);

/// Throws GpuError naming call and status when status is not CL_SUCCESS.
inline void checkCl(cl_int status, const char* call) {
  if (status != CL_SUCCESS) [[unlikely]] {
    throw GpuError(
        std::string(call) + " failed: " + clErrorName(status) + " (" + std::to_string(status) + ")",
        status);
  }
}

}  // namespace zonesim::gpu
