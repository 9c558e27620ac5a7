#pragma once
// A dynamic AABB tree (as in Box2D and Bullet's btDbvt): leaves hold fattened boxes, so a body
// that moves a little needs no tree update; one that leaves its fat box is reinserted.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/aabb.h"

namespace zonesim::physics {

/// A binary tree of boxes over proxies 0..n-1, updated incrementally between steps.
class AabbTree {
 public:
  /// Brings the tree up to date with the proxies' tight boxes (rebuilt if n changed).
  void update(std::span<const Aabb> boxes);
  /// Appends every pair (i < j) whose tight boxes overlap and where one of them moves.
  void collectPairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                    std::vector<ProxyPair>& out);

 private:
  static constexpr std::int32_t kNull = -1;
  struct Node {
    Aabb box;
    std::int32_t parent = kNull;
    std::int32_t left = kNull;
    std::int32_t right = kNull;
    std::int32_t proxy = kNull;  // Leaf when not kNull.
  };

  std::int32_t allocate();
  void insertLeaf(std::int32_t leaf);
  void removeLeaf(std::int32_t leaf);
  void refitUp(std::int32_t node);

  std::vector<Node> nodes_;
  std::vector<std::int32_t> free_;
  std::vector<std::int32_t> leaf_of_proxy_;
  std::vector<std::int32_t> stack_;
  std::int32_t root_ = kNull;
  double margin_ = 0.1;  // Fattening (m): trades looser culling for fewer reinsertions.
};

}  // namespace zonesim::physics
