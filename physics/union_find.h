#pragma once
// Disjoint sets over body indices, for the islands of sleeping and of level of detail: the
// smaller index becomes the root, so an island's id is its lowest body and does not depend on
// the order of the links.

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

namespace zonesim::physics {

/// Union-find with path halving over 0..n-1.
class UnionFind {
 public:
  /// n singletons (keeps the capacity).
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0u);
  }
  /// The root of i's set: its lowest member.
  std::uint32_t find(std::uint32_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];  // Path halving.
      i = parent_[i];
    }
    return i;
  }
  /// Joins the sets of a and b.
  void unite(std::uint32_t a, std::uint32_t b) {
    const std::uint32_t ra = find(a), rb = find(b);
    if (ra != rb) parent_[std::max(ra, rb)] = std::min(ra, rb);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace zonesim::physics
