#include "gpu/default_runtime.h"

#include <mutex>

#include "gpu/cl_runtime.h"

namespace zonesim::gpu {

std::shared_ptr<ClRuntime> defaultRuntime() {
  static std::mutex mutex;
  static std::weak_ptr<ClRuntime> shared;
  std::lock_guard<std::mutex> lock(mutex);
  std::shared_ptr<ClRuntime> runtime = shared.lock();
  if (!runtime) {
    runtime = std::make_shared<ClRuntime>();
    shared = runtime;
  }
  return runtime;
}

}  // namespace zonesim::gpu
