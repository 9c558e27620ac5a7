#pragma once
// Owning wrappers for OpenCL objects: released exactly once, movable, never copied, so an
// exception thrown half-way through setting up a runtime leaks nothing. Internal to gpu/.

#include <utility>

#include "gpu/cl_api.h"

namespace zonesim::gpu {

/// Owns one OpenCL object of type T and calls Release on it when dropped.
template <typename T, auto Release>
class ClHandle {
 public:
  ClHandle() = default;
  /// Takes ownership of an object returned by a clCreate* call.
  explicit ClHandle(T handle) : handle_(handle) {}
  ~ClHandle() { reset(); }
  ClHandle(const ClHandle&) = delete;
  ClHandle& operator=(const ClHandle&) = delete;
  ClHandle(ClHandle&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  ClHandle& operator=(ClHandle&& other) noexcept {
    if (this != &other) reset(std::exchange(other.handle_, nullptr));
    return *this;
  }

  /// The raw handle, still owned by this wrapper.
  T get() const { return handle_; }
  /// True when an object is held.
  explicit operator bool() const { return handle_ != nullptr; }
  /// Releases the held object (if any) and takes h instead.
  void reset(T handle = nullptr) {
    if (handle_) Release(handle_);
    handle_ = handle;
  }

 private:
  T handle_ = nullptr;
};

using ClContext = ClHandle<cl_context, clReleaseContext>;
using ClQueue = ClHandle<cl_command_queue, clReleaseCommandQueue>;
using ClProgramHandle = ClHandle<cl_program, clReleaseProgram>;
using ClKernelHandle = ClHandle<cl_kernel, clReleaseKernel>;
using ClBuffer = ClHandle<cl_mem, clReleaseMemObject>;
using ClEvent = ClHandle<cl_event, clReleaseEvent>;

}  // namespace zonesim::gpu
