#include "gpu/cl_program.h"

#include <utility>

namespace zonesim::gpu {

ClKernel::ClKernel(ClKernelHandle kernel, std::string name)
    : kernel_(std::move(kernel)), name_(std::move(name)) {}

void ClKernel::setArgBytes(cl_uint index, std::size_t size, const void* value) {
  cl_int status = clSetKernelArg(kernel_.get(), index, size, value);
  if (status != CL_SUCCESS) {
    std::string call = "clSetKernelArg(" + name_ + ", arg " + std::to_string(index) + ")";
    checkCl(status, call.c_str());
  }
}

void ClKernel::enqueue(cl_command_queue queue, std::size_t global_size) {
  cl_int status = clEnqueueNDRangeKernel(queue, kernel_.get(), 1, nullptr, &global_size, nullptr, 0,
                                         nullptr, nullptr);
  if (status != CL_SUCCESS) {
    std::string call = "clEnqueueNDRangeKernel(" + name_ + ")";
    checkCl(status, call.c_str());
  }
}

void ClKernel::enqueue(cl_command_queue queue, std::size_t global_size, std::size_t local_size) {
  cl_int status = clEnqueueNDRangeKernel(queue, kernel_.get(), 1, nullptr, &global_size,
                                         &local_size, 0, nullptr, nullptr);
  if (status != CL_SUCCESS) {
    std::string call = "clEnqueueNDRangeKernel(" + name_ + ")";
    checkCl(status, call.c_str());
  }
}

ClProgram::ClProgram(ClProgramHandle program, std::string name)
    : program_(std::move(program)), name_(std::move(name)) {}

ClKernel ClProgram::createKernel(const std::string& kernel_name) const {
  cl_int status = CL_SUCCESS;
  cl_kernel kernel = clCreateKernel(program_.get(), kernel_name.c_str(), &status);
  if (status != CL_SUCCESS) {
    std::string call = "clCreateKernel(" + name_ + ", " + kernel_name + ")";
    checkCl(status, call.c_str());
  }
  return ClKernel(ClKernelHandle(kernel), kernel_name);
}

}  // namespace zonesim::gpu
