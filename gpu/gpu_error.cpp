#include "gpu/gpu_error.h"

namespace zonesim::gpu {

GpuError::GpuError(const std::string& message, int code)
    : std::runtime_error(message), code_(code) {}

}  // namespace zonesim::gpu
