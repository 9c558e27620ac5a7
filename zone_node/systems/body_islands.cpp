#include "zone_node/systems/body_islands.h"

#include <algorithm>
#include <bit>
#include <numeric>
#include <stdexcept>
#include <string>

#include "physics/union_find.h"

namespace zonesim::zone {

namespace {

/// Calls join(i, j) for every pair of overlapping boxes (sweep along x).
template <typename Join>
void forOverlaps(std::span<const physics::Aabb> boxes, Join&& join) {
  std::vector<std::uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return boxes[a].lo.x() != boxes[b].lo.x() ? boxes[a].lo.x() < boxes[b].lo.x() : a < b;
  });
  for (std::size_t k = 0; k < order.size(); ++k) {
    const physics::Aabb& a = boxes[order[k]];
    for (std::size_t m = k + 1; m < order.size() && boxes[order[m]].lo.x() <= a.hi.x(); ++m)
      if (a.overlaps(boxes[order[m]])) join(order[k], order[m]);
  }
}

}  // namespace

std::vector<EntityId> joinOverlapping(std::span<const EntityId> ids,
                                      std::span<const physics::Aabb> boxes,
                                      std::span<const IndexLink> links) {
  physics::UnionFind sets;
  sets.reset(ids.size());
  forOverlaps(boxes, [&](std::uint32_t a, std::uint32_t b) { sets.unite(a, b); });
  for (auto [a, b] : links) sets.unite(a, b);
  // The root is the lowest index, and ids ascend: the root's id is the island's lowest.
  std::vector<EntityId> label(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) label[i] = ids[sets.find(std::uint32_t(i))];
  return label;
}

std::unordered_map<std::uint64_t, IslandSolver> joinAcrossZones(std::span<const BorderBody> shared,
                                                                std::span<const BodyLink> links) {
  // One node per zone island (label), numbered in label order so the root is the lowest.
  std::vector<std::uint64_t> labels;
  for (const BorderBody& b : shared) labels.push_back(b.label.value);
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  auto node = [&](EntityId label) {
    return std::uint32_t(std::lower_bound(labels.begin(), labels.end(), label.value) -
                         labels.begin());
  };
  std::vector<int> rank_of(labels.size(), 0);
  for (const BorderBody& b : shared) rank_of[node(b.label)] = b.rank;
  std::vector<physics::Aabb> boxes;
  boxes.reserve(shared.size());
  for (const BorderBody& b : shared) boxes.push_back(b.box);
  physics::UnionFind sets;
  sets.reset(labels.size());
  forOverlaps(boxes, [&](std::uint32_t a, std::uint32_t b) {
    if (shared[a].rank != shared[b].rank) sets.unite(node(shared[a].label), node(shared[b].label));
  });
  if (!links.empty()) {
    std::unordered_map<std::uint64_t, EntityId> label_of;
    for (const BorderBody& b : shared)
      if (b.body) label_of[b.body.value] = b.label;
    for (const auto& [a, b] : links) {
      auto la = label_of.find(a.value), lb = label_of.find(b.value);
      if (la != label_of.end() && lb != label_of.end())
        sets.unite(node(la->second), node(lb->second));
    }
  }
  std::unordered_map<std::uint64_t, IslandSolver> out;
  for (std::size_t n = 0; n < labels.size(); ++n) {
    const std::uint32_t root = sets.find(std::uint32_t(n));
    out[labels[n]] = IslandSolver{EntityId{labels[root]}, rank_of[root]};
  }
  return out;
}

void appendWords(const BorderBody& b, std::vector<std::uint64_t>& out) {
  out.push_back(b.label.value);
  out.push_back(b.body.value);
  out.push_back(std::uint64_t(b.rank));
  for (const Vec3* v : {&b.box.lo, &b.box.hi})
    for (int k = 0; k < 3; ++k) out.push_back(std::bit_cast<std::uint64_t>((*v)[k]));
}

std::vector<BorderBody> borderBodiesOf(std::span<const std::uint64_t> words) {
  if (words.size() % kBorderBodyWords != 0)
    throw std::runtime_error("border bodies: " + std::to_string(words.size()) +
                             " words is not a whole number of " + std::to_string(kBorderBodyWords) +
                             "-word records");
  std::vector<BorderBody> out(words.size() / kBorderBodyWords);
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::uint64_t* w = &words[i * kBorderBodyWords];
    out[i].label = EntityId{w[0]};
    out[i].body = EntityId{w[1]};
    out[i].rank = int(w[2]);
    for (int k = 0; k < 3; ++k) {
      out[i].box.lo[k] = std::bit_cast<double>(w[3 + k]);
      out[i].box.hi[k] = std::bit_cast<double>(w[6 + k]);
    }
  }
  return out;
}

}  // namespace zonesim::zone
