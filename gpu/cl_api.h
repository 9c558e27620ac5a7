#pragma once
// The one place that includes the OpenCL C API, pinned to 1.2 so that the code builds and runs
// the same on PoCL and on GPU drivers (no 2.x-only calls slip in). Internal to gpu/.

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#include <CL/cl.h>
