#include "gpu/cl_sort.h"

#include <algorithm>
#include <bit>

#include "gpu/cl_error.h"

namespace zonesim::gpu {
namespace {

// 256 work items (512 pairs, 4 KiB of local memory) suit both GPUs and PoCL's CPU devices.
constexpr std::size_t kPreferredLocal = 256;

}  // namespace

ClPairSort::ClPairSort(std::shared_ptr<const ClRuntime> runtime)
    : runtime_(std::move(runtime)),
      program_(runtime_->buildEmbeddedProgram("sort")),
      global_(program_.createKernel("bitonic_global")),
      local_(program_.createKernel("bitonic_local")) {
  std::size_t kernel_max = 0;
  checkCl(clGetKernelWorkGroupInfo(local_.handle(), runtime_->device(), CL_KERNEL_WORK_GROUP_SIZE,
                                   sizeof(kernel_max), &kernel_max, nullptr),
          "clGetKernelWorkGroupInfo");
  cl_ulong local_mem = 0;
  checkCl(clGetDeviceInfo(runtime_->device(), CL_DEVICE_LOCAL_MEM_SIZE, sizeof(local_mem),
                          &local_mem, nullptr),
          "clGetDeviceInfo");
  // Two uint arrays of two elements per work item must fit in local memory.
  std::size_t by_memory = std::size_t(local_mem / (4 * sizeof(cl_uint)));
  max_local_ =
      std::bit_floor(std::max<std::size_t>(1, std::min({kPreferredLocal, kernel_max, by_memory})));
}

std::size_t ClPairSort::paddedLength(std::size_t n) {
  return std::bit_ceil(std::max<std::size_t>(n, 2));
}

std::size_t ClPairSort::enqueue(cl_mem keys, cl_mem vals, std::size_t padded_length) {
  const std::size_t pairs = padded_length / 2;
  const std::size_t local = std::min(max_local_, pairs);
  const std::size_t span = 2 * local;
  cl_command_queue queue = runtime_->queue();
  std::size_t launches = 0;
  global_.setArg(0, keys);
  global_.setArg(1, vals);
  local_.setArg(0, keys);
  local_.setArg(1, vals);
  local_.setArgBytes(2, span * sizeof(cl_uint), nullptr);
  local_.setArgBytes(3, span * sizeof(cl_uint), nullptr);
  // Every level up to the block span at once, inside each block.
  local_.setArg(4, cl_uint(2));
  local_.setArg(5, cl_uint(span));
  local_.enqueue(queue, pairs, local);
  ++launches;
  for (std::size_t k = 2 * span; k <= padded_length; k <<= 1) {
    for (std::size_t j = k / 2; j >= span; j >>= 1) {
      global_.setArg(2, cl_uint(j));
      global_.setArg(3, cl_uint(k));
      global_.enqueue(queue, pairs);
      ++launches;
    }
    // The stages below the block span finish level k in local memory.
    local_.setArg(4, cl_uint(k));
    local_.setArg(5, cl_uint(k));
    local_.enqueue(queue, pairs, local);
    ++launches;
  }
  return launches;
}

}  // namespace zonesim::gpu
