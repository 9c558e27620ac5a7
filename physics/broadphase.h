#pragma once
// Broadphase: candidate pairs whose boxes overlap and of which at least one moves. Four
// algorithms, one selected per scene; all return the same sorted pair set.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/aabb.h"
#include "physics/aabb_tree.h"

namespace zonesim::physics {

/// The broadphase algorithms.
enum class BroadphaseKind : std::uint8_t { BruteForce, SweepAndPrune, UniformGrid, AabbTree };

/// Finds overlapping proxy pairs with the selected algorithm; keeps its buffers between calls.
class Broadphase {
 public:
  /// Creates a broadphase of the given kind; grid_cell is the uniform grid's cell size (m).
  explicit Broadphase(BroadphaseKind kind, double grid_cell = 2.0);

  /// Replaces out with the sorted pairs (i < j) whose boxes overlap and where moving[i] or
  /// moving[j] is non-zero.
  void findPairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                 std::vector<ProxyPair>& out);

  /// The algorithm in use.
  BroadphaseKind kind() const { return kind_; }

 private:
  void bruteForce(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                  std::vector<ProxyPair>& out) const;
  void sweepAndPrune(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                     std::vector<ProxyPair>& out);
  void uniformGrid(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                   std::vector<ProxyPair>& out);

  BroadphaseKind kind_;
  double cell_;
  std::vector<std::uint32_t> order_;  // Sweep order by lower x bound.
  struct Swept {
    Aabb box;
    std::uint32_t index;
    bool moving;
  };
  std::vector<Swept> swept_;  // The boxes in sweep order.
  std::vector<std::uint32_t> pair_start_;
  std::vector<ProxyPair> pair_scratch_;
  std::vector<std::uint64_t> cells_;  // Grid: (cell hash << 32 | proxy), sorted.
  std::vector<std::uint32_t> oversized_;
  AabbTree tree_;
};

}  // namespace zonesim::physics
