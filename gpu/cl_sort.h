#pragma once
// Sorting (key, value) uint pairs in device buffers with a bitonic network (gpu/kernels/sort.cl),
// so that a grid can be built without a round trip to the host. Internal to gpu/.

#include <cstddef>
#include <memory>

#include "gpu/cl_runtime.h"

namespace zonesim::gpu {

class ClPairSort {
 public:
  /// Builds the sort kernels on runtime's device; throws GpuError on failure.
  explicit ClPairSort(std::shared_ptr<const ClRuntime> runtime);

  /// The padded length a buffer must have to sort n pairs: the next power of two, at least 2.
  static std::size_t paddedLength(std::size_t n);
  /// Queues the sort of keys/vals (padded_length pairs, a power of two) by key, then value.
  /// Returns the number of launches it queued.
  std::size_t enqueue(cl_mem keys, cl_mem vals, std::size_t padded_length);

 private:
  std::shared_ptr<const ClRuntime> runtime_;
  ClProgram program_;
  ClKernel global_;
  ClKernel local_;
  // Largest power-of-two work-group size the local kernel may use on this device.
  std::size_t max_local_ = 1;
};

}  // namespace zonesim::gpu
