#pragma once
// OpenCL C sources embedded at build time from gpu/kernels/*.cl (see embed_kernels.cmake).

#include <span>
#include <string_view>

namespace zonesim::gpu {

/// One embedded kernel file: its stem and its full text.
struct KernelSource {
  std::string_view name;
  std::string_view text;
};

/// Every embedded kernel file, sorted by name (defined in the generated source).
std::span<const KernelSource> kernelSources();

/// The text of the kernel file with this stem; throws std::out_of_range when there is none.
std::string_view kernelSource(std::string_view name);

}  // namespace zonesim::gpu
