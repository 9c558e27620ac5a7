#pragma once
// The process's shared OpenCL device for systems built without an explicit runtime. Internal to
// gpu/.

#include <memory>

namespace zonesim::gpu {

class ClRuntime;

/// One context and queue per process (first GPU, else a CPU device), alive while some system
/// uses it; throws NoDeviceError when there is no device.
std::shared_ptr<ClRuntime> defaultRuntime();

}  // namespace zonesim::gpu
