#pragma once
// A bounded uniform sample of a stream (reservoir sampling, Algorithm R), so percentiles of
// per-update figures stay cheap and memory stays flat however long a run lasts.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "common/rng.h"

namespace zonesim::clients {

class Reservoir {
 public:
  explicit Reservoir(std::size_t capacity = 4096, std::uint64_t seed = 1)
      : capacity_(capacity), rng_(seed, 0x7e5e) {}

  /// Offers one value; every value seen so far is kept with equal probability.
  void add(double v) {
    max_ = std::max(max_, v);
    ++seen_;
    if (samples_.size() < capacity_) {
      samples_.push_back(v);
      return;
    }
    std::uint64_t j = std::uint64_t(rng_.uniform() * double(seen_));
    if (j < capacity_) samples_[j] = v;
  }
  /// Appends another reservoir's samples (for totals; an approximation when both are full).
  void merge(const Reservoir& o) {
    samples_.insert(samples_.end(), o.samples_.begin(), o.samples_.end());
    max_ = std::max(max_, o.max_);
  }
  const std::vector<double>& samples() const { return samples_; }
  std::uint64_t seen() const { return seen_; }
  /// The largest value offered (kept or not), or of any merged reservoir; 0 before any.
  double max() const { return max_ == kNone ? 0.0 : max_; }

 private:
  std::size_t capacity_;
  Pcg32 rng_;
  std::vector<double> samples_;
  std::uint64_t seen_ = 0;
  static constexpr double kNone = -std::numeric_limits<double>::infinity();
  double max_ = kNone;
};

}  // namespace zonesim::clients
