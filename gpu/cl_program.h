#pragma once
// A built OpenCL program and the kernels taken from it. Internal to gpu/.

#include <cstddef>
#include <string>

#include "gpu/cl_error.h"
#include "gpu/cl_handles.h"

namespace zonesim::gpu {

/// One kernel of a program, with argument setting and launch that throw on failure.
class ClKernel {
 public:
  /// Takes ownership of kernel; name is kept for error messages.
  ClKernel(ClKernelHandle kernel, std::string name);

  /// Sets argument index to value (a scalar or a cl_mem); throws naming the kernel and index.
  template <typename T>
  void setArg(cl_uint index, const T& value) {
    setArgBytes(index, sizeof(T), &value);
  }
  /// Sets argument index from raw bytes; exposed so that a wrong size can be shown to fail.
  void setArgBytes(cl_uint index, std::size_t size, const void* value);
  /// Enqueues a 1-D launch over global_size work items (local size left to the driver).
  void enqueue(cl_command_queue queue, std::size_t global_size);
  /// Enqueues a 1-D launch in work-groups of local_size (global_size must be a multiple).
  void enqueue(cl_command_queue queue, std::size_t global_size, std::size_t local_size);
  /// The raw kernel, for queries this class does not wrap.
  cl_kernel handle() const { return kernel_.get(); }
  /// The kernel function's name.
  const std::string& name() const { return name_; }

 private:
  ClKernelHandle kernel_;
  std::string name_;
};

/// A program built for one device; kernels are created from it by name.
class ClProgram {
 public:
  /// Takes ownership of a successfully built program.
  ClProgram(ClProgramHandle program, std::string name);
  /// Creates the kernel called kernel_name; throws CL_INVALID_KERNEL_NAME if there is none.
  ClKernel createKernel(const std::string& kernel_name) const;
  /// The name the program was built under (the kernel file's stem).
  const std::string& name() const { return name_; }

 private:
  ClProgramHandle program_;
  std::string name_;
};

}  // namespace zonesim::gpu
