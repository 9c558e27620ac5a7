#pragma once
// Summary statistics over samples (tick times, gaps): percentiles by nearest rank.

#include <algorithm>
#include <cmath>
#include <vector>

namespace zonesim {

/// The p-th percentile (0..100) by nearest rank; 0 for no samples. Sorts a copy.
inline double percentile(std::vector<double> samples, double p) {
  if (samples.empty()) return 0.0;
  std::sort(samples.begin(), samples.end());
  // p * n first: p / 100 is inexact (0.07 * 100 = 7.000000000000001 would round up a rank).
  double rank = std::ceil(p * double(samples.size()) / 100.0);
  std::size_t i = rank < 1 ? 0 : std::size_t(rank) - 1;
  return samples[std::min(i, samples.size() - 1)];
}

}  // namespace zonesim
