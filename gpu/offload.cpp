#include "gpu/offload.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace zonesim::gpu {

const char* workloadName(Workload workload) {
  switch (workload) {
    case Workload::Particles:
      return "particles";
    case Workload::Flock:
      return "flock";
  }
  return "unknown";
}

std::size_t OffloadThresholds::of(Workload workload) const {
  switch (workload) {
    case Workload::Particles:
      return particles;
    case Workload::Flock:
      return flock;
  }
  return kNeverOffload;
}

OffloadThresholds defaultThresholds() {
  return OffloadThresholds{};
}

std::size_t crossover(std::span<const ProbeSample> samples) {
  std::vector<ProbeSample> sorted(samples.begin(), samples.end());
  std::sort(sorted.begin(), sorted.end(), [](auto& a, auto& b) { return a.n < b.n; });
  if (sorted.empty() || !(sorted.back().device_s < sorted.back().cpu_s)) return kNeverOffload;
  // The first probe of the winning run that reaches the largest size.
  std::size_t first = sorted.size() - 1;
  while (first > 0 && sorted[first - 1].device_s < sorted[first - 1].cpu_s) --first;
  if (first == 0) return sorted.front().n;
  const ProbeSample& lose = sorted[first - 1];
  const ProbeSample& win = sorted[first];
  // Margins in log(cpu / device): <= 0 at lose, > 0 at win; zero crossing in log n between.
  double a = std::log(lose.cpu_s / lose.device_s);
  double b = std::log(win.cpu_s / win.device_s);
  double t = a < b ? -a / (b - a) : 1.0;
  double n =
      std::exp(std::log(double(lose.n)) + t * (std::log(double(win.n)) - std::log(double(lose.n))));
  return std::clamp(static_cast<std::size_t>(std::ceil(n)), lose.n + 1, win.n);
}

Backend chooseBackend(GpuMode mode, Workload workload, std::size_t n, bool opencl_available,
                      const OffloadThresholds& thresholds) {
  return chooseBackend(mode, opencl_available && n >= thresholds.of(workload));
}

}  // namespace zonesim::gpu
