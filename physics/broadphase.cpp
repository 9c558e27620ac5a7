#include "physics/broadphase.h"

#include <algorithm>
#include <cmath>

namespace zonesim::physics {

namespace {
// A proxy covering more grid cells than this is tested against all others instead: one huge
// floor would otherwise fill thousands of cells.
constexpr std::int64_t kMaxCellsPerProxy = 64;

bool wanted(std::span<const std::uint8_t> moving, std::uint32_t i, std::uint32_t j) {
  return moving[i] || moving[j];
}
}  // namespace

Broadphase::Broadphase(BroadphaseKind kind, double grid_cell) : kind_(kind), cell_(grid_cell) {}

void Broadphase::findPairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                           std::vector<ProxyPair>& out) {
  out.clear();
  switch (kind_) {
    case BroadphaseKind::BruteForce:
      bruteForce(boxes, moving, out);
      break;
    case BroadphaseKind::SweepAndPrune:
      sweepAndPrune(boxes, moving, out);
      break;
    case BroadphaseKind::UniformGrid:
      uniformGrid(boxes, moving, out);
      break;
    case BroadphaseKind::AabbTree:
      tree_.update(boxes);
      tree_.collectPairs(boxes, moving, out);
      break;
  }
  // One canonical order for every algorithm: the solver's result depends on pair order.
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

void Broadphase::bruteForce(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                            std::vector<ProxyPair>& out) const {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t j = i + 1; j < n; ++j) {
      if (wanted(moving, i, j) && boxes[i].overlaps(boxes[j])) out.push_back({i, j});
    }
  }
}

void Broadphase::sweepAndPrune(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                               std::vector<ProxyPair>& out) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  // The previous order is nearly sorted after a small step; insertion-friendly std::sort is
  // still O(n log n) but the comparison is cheap.
  if (order_.size() != n) {
    order_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) order_[i] = i;
  }
  std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
    return boxes[a].lo.x() != boxes[b].lo.x() ? boxes[a].lo.x() < boxes[b].lo.x() : a < b;
  });
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t i = order_[k];
    const double hi_x = boxes[i].hi.x();
    for (std::uint32_t m = k + 1; m < n; ++m) {
      const std::uint32_t j = order_[m];
      if (boxes[j].lo.x() > hi_x) break;
      if (wanted(moving, i, j) && boxes[i].overlaps(boxes[j])) {
        out.push_back(i < j ? ProxyPair{i, j} : ProxyPair{j, i});
      }
    }
  }
}

void Broadphase::uniformGrid(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                             std::vector<ProxyPair>& out) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  cells_.clear();
  oversized_.clear();
  const double inv = 1.0 / cell_;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Eigen::Array3d lo = (boxes[i].lo * inv).array().floor();
    const Eigen::Array3d hi = (boxes[i].hi * inv).array().floor();
    const Eigen::Array3d span = hi - lo + 1.0;
    if (!span.allFinite() || span.prod() > double(kMaxCellsPerProxy)) {
      oversized_.push_back(i);
      continue;
    }
    for (auto x = std::int64_t(lo.x()); x <= std::int64_t(hi.x()); ++x) {
      for (auto y = std::int64_t(lo.y()); y <= std::int64_t(hi.y()); ++y) {
        for (auto z = std::int64_t(lo.z()); z <= std::int64_t(hi.z()); ++z) {
          // Spatial hash (Teschner et al.); collisions only add candidates, never lose them.
          const auto h =
              static_cast<std::uint32_t>((x * 73856093) ^ (y * 19349663) ^ (z * 83492791));
          cells_.push_back((std::uint64_t(h) << 32) | i);
        }
      }
    }
  }
  std::sort(cells_.begin(), cells_.end());
  for (std::size_t a = 0; a < cells_.size();) {
    std::size_t b = a;
    while (b < cells_.size() && (cells_[b] >> 32) == (cells_[a] >> 32)) ++b;
    for (std::size_t p = a; p < b; ++p) {
      for (std::size_t q = p + 1; q < b; ++q) {
        const auto i = static_cast<std::uint32_t>(cells_[p]);
        const auto j = static_cast<std::uint32_t>(cells_[q]);
        // Two of one proxy's cells can share a hash.
        if (i == j) continue;
        if (wanted(moving, i, j) && boxes[i].overlaps(boxes[j])) out.push_back({i, j});
      }
    }
    a = b;
  }
  for (std::uint32_t big : oversized_) {
    for (std::uint32_t j = 0; j < n; ++j) {
      if (j == big || !wanted(moving, big, j) || !boxes[big].overlaps(boxes[j])) continue;
      out.push_back(big < j ? ProxyPair{big, j} : ProxyPair{j, big});
    }
  }
}

}  // namespace zonesim::physics
