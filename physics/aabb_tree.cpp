#include "physics/aabb_tree.h"

namespace zonesim::physics {

std::int32_t AabbTree::allocate() {
  if (!free_.empty()) {
    const std::int32_t n = free_.back();
    free_.pop_back();
    nodes_[n] = Node{};
    return n;
  }
  nodes_.push_back(Node{});
  return static_cast<std::int32_t>(nodes_.size() - 1);
}

void AabbTree::refitUp(std::int32_t node) {
  while (node != kNull) {
    Node& n = nodes_[node];
    n.box = nodes_[n.left].box.merged(nodes_[n.right].box);
    node = n.parent;
  }
}

void AabbTree::insertLeaf(std::int32_t leaf) {
  if (root_ == kNull) {
    root_ = leaf;
    nodes_[leaf].parent = kNull;
    return;
  }
  // Descend towards the child whose surface area grows least (greedy SAH).
  const Aabb box = nodes_[leaf].box;
  std::int32_t sibling = root_;
  while (nodes_[sibling].proxy == kNull) {
    const Node& n = nodes_[sibling];
    const double grow_left = nodes_[n.left].box.merged(box).area() - nodes_[n.left].box.area();
    const double grow_right = nodes_[n.right].box.merged(box).area() - nodes_[n.right].box.area();
    sibling = grow_left <= grow_right ? n.left : n.right;
  }
  const std::int32_t old_parent = nodes_[sibling].parent;
  const std::int32_t parent = allocate();
  nodes_[parent].parent = old_parent;
  nodes_[parent].left = sibling;
  nodes_[parent].right = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent == kNull) {
    root_ = parent;
  } else if (nodes_[old_parent].left == sibling) {
    nodes_[old_parent].left = parent;
  } else {
    nodes_[old_parent].right = parent;
  }
  refitUp(parent);
}

void AabbTree::removeLeaf(std::int32_t leaf) {
  if (leaf == root_) {
    root_ = kNull;
    return;
  }
  const std::int32_t parent = nodes_[leaf].parent;
  const std::int32_t grand = nodes_[parent].parent;
  const std::int32_t sibling =
      nodes_[parent].left == leaf ? nodes_[parent].right : nodes_[parent].left;
  if (grand == kNull) {
    root_ = sibling;
    nodes_[sibling].parent = kNull;
  } else {
    if (nodes_[grand].left == parent) {
      nodes_[grand].left = sibling;
    } else {
      nodes_[grand].right = sibling;
    }
    nodes_[sibling].parent = grand;
    refitUp(grand);
  }
  free_.push_back(parent);
}

void AabbTree::update(std::span<const Aabb> boxes) {
  const auto n = static_cast<std::int32_t>(boxes.size());
  if (static_cast<std::int32_t>(leaf_of_proxy_.size()) != n) {
    nodes_.clear();
    free_.clear();
    root_ = kNull;
    leaf_of_proxy_.assign(n, kNull);
    for (std::int32_t i = 0; i < n; ++i) {
      const std::int32_t leaf = allocate();
      nodes_[leaf].box = boxes[i].expanded(margin_);
      nodes_[leaf].proxy = i;
      leaf_of_proxy_[i] = leaf;
      insertLeaf(leaf);
    }
    return;
  }
  for (std::int32_t i = 0; i < n; ++i) {
    const std::int32_t leaf = leaf_of_proxy_[i];
    if (nodes_[leaf].box.contains(boxes[i])) continue;
    removeLeaf(leaf);
    nodes_[leaf].box = boxes[i].expanded(margin_);
    insertLeaf(leaf);
  }
}

void AabbTree::collectPairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                            std::vector<ProxyPair>& out) {
  if (root_ == kNull) return;
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    // Only moving proxies query: static-static pairs are never wanted.
    if (!moving[i]) continue;
    stack_.clear();
    stack_.push_back(root_);
    while (!stack_.empty()) {
      const Node& node = nodes_[stack_.back()];
      stack_.pop_back();
      if (!node.box.overlaps(boxes[i])) continue;
      if (node.proxy == kNull) {
        stack_.push_back(node.left);
        stack_.push_back(node.right);
        continue;
      }
      const auto j = static_cast<std::uint32_t>(node.proxy);
      // A moving pair is reported by its lower index; a static partner by the mover.
      if (j == i || (moving[j] && j < i)) continue;
      if (!boxes[i].overlaps(boxes[j])) continue;
      out.push_back(i < j ? ProxyPair{i, j} : ProxyPair{j, i});
    }
  }
}

}  // namespace zonesim::physics
