#include "gpu/kernel_sources.h"

#include <stdexcept>
#include <string>

namespace zonesim::gpu {

std::string_view kernelSource(std::string_view name) {
  for (const KernelSource& source : kernelSources()) {
    if (source.name == name) return source.text;
  }
  throw std::out_of_range("no embedded OpenCL kernel file '" + std::string(name) +
                          ".cl' in gpu/kernels/");
}

}  // namespace zonesim::gpu
