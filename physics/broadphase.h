#pragma once
// Broadphase: candidate pairs whose boxes overlap and of which at least one moves. Four
// algorithms, one selected per scene; all return the same sorted pair set. With a keep margin,
// the pairs of the boxes grown by it are kept from step to step (as Box2D's fat boxes), and a
// step only filters them, looking again at the few boxes that left their grown ones.

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
  /// Creates a broadphase of the given kind; grid_cell is the uniform grid's cell size (m);
  /// keep_margin (m), where positive, keeps the pairs of boxes grown by it between calls.
  explicit Broadphase(BroadphaseKind kind, double grid_cell = 2.0, double keep_margin = 0.0);

  /// Replaces out with the sorted pairs (i < j) whose boxes overlap and where moving[i] or
  /// moving[j] is non-zero.
  void findPairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                 std::vector<ProxyPair>& out);

  /// The algorithm in use.
  BroadphaseKind kind() const { return kind_; }
  /// Kept pairs: how often the grown boxes' pairs were all found anew, and how many boxes
  /// were looked at again alone, since construction.
  std::size_t rebuilds() const { return rebuilds_; }
  std::size_t regrown() const { return regrown_; }

 private:
  // Every overlapping pair with the selected algorithm, sorted.
  void findAll(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
               std::vector<ProxyPair>& out);
  // The kept pairs brought up to date, then filtered down to the boxes' own overlaps.
  void findFromKept(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                    std::vector<ProxyPair>& out);
  // Grows the escaped boxes anew and replaces their kept pairs.
  void regrow(std::span<const Aabb> boxes);
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
  // Kept pairs: every pair (either moving or not) whose grown boxes overlap, sorted; each
  // box lies inside its grown one.
  double keep_margin_;
  std::vector<Aabb> grown_;
  std::vector<ProxyPair> kept_, fresh_;
  std::vector<std::uint32_t> escaped_;
  std::vector<std::uint8_t> is_escaped_, all_moving_;
  std::size_t rebuilds_ = 0, regrown_ = 0;
};

}  // namespace zonesim::physics
