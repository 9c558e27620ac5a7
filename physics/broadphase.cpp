#include "physics/broadphase.h"

#include <algorithm>
#include <cmath>

namespace zonesim::physics {

namespace {
// A proxy covering more grid cells than this is tested against all others instead: one huge
// floor would otherwise fill thousands of cells.
constexpr std::int64_t kMaxCellsPerProxy = 64;
// Kept pairs: the most boxes looked at again alone in one call before all are found anew.
constexpr std::size_t kMaxRegrown = 32;

bool wanted(std::span<const std::uint8_t> moving, std::uint32_t i, std::uint32_t j) {
  return moving[i] || moving[j];
}

// Sorts v by less with insertion sort, giving up (false, v a permutation of what it was) once
// more than `budget` elements have been moved.
template <class Less>
bool insertionSort(std::vector<std::uint32_t>& v, const Less& less, std::size_t budget) {
  std::size_t moves = 0;
  for (std::size_t k = 1; k < v.size(); ++k) {
    const std::uint32_t x = v[k];
    std::size_t at = k;
    while (at > 0 && less(x, v[at - 1])) {
      v[at] = v[at - 1];
      --at;
      if (++moves > budget) {
        v[at] = x;
        return false;
      }
    }
    v[at] = x;
  }
  return true;
}

// Sorts pairs by (first, second) with a counting sort on the first index (proxies < n) and
// insertion sort within each first index's few pairs: about linear where std::sort is n log n.
void sortPairs(std::vector<ProxyPair>& pairs, std::size_t n, std::vector<std::uint32_t>& start,
               std::vector<ProxyPair>& scratch) {
  start.assign(n + 1, 0);
  for (const ProxyPair& p : pairs) ++start[p.first + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  scratch.resize(pairs.size());
  for (const ProxyPair& p : pairs) scratch[start[p.first]++] = p;
  // start[i] is now the end of first index i's run, and the run begins at start[i - 1].
  for (std::size_t i = 0, begin = 0; i < n; begin = start[i], ++i) {
    // A big run (a floor paired with everything on it) is sorted the usual way.
    if (start[i] - begin > 32) {
      std::sort(scratch.begin() + begin, scratch.begin() + start[i]);
      continue;
    }
    for (std::size_t k = begin + 1; k < start[i]; ++k) {
      const ProxyPair x = scratch[k];
      std::size_t at = k;
      while (at > begin && x.second < scratch[at - 1].second) {
        scratch[at] = scratch[at - 1];
        --at;
      }
      scratch[at] = x;
    }
  }
  pairs.swap(scratch);
}
}  // namespace

Broadphase::Broadphase(BroadphaseKind kind, double grid_cell, double keep_margin)
    : kind_(kind), cell_(grid_cell), keep_margin_(keep_margin) {}

void Broadphase::findPairs(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                           std::vector<ProxyPair>& out) {
  out.clear();
  if (keep_margin_ > 0.0) {
    findFromKept(boxes, moving, out);
  } else {
    findAll(boxes, moving, out);
  }
}

void Broadphase::findFromKept(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
                              std::vector<ProxyPair>& out) {
  const std::size_t n = boxes.size();
  escaped_.clear();
  bool rebuild = grown_.size() != n;
  for (std::size_t i = 0; !rebuild && i < n; ++i) {
    if (!grown_[i].contains(boxes[i])) escaped_.push_back(static_cast<std::uint32_t>(i));
    // Each escaped box is compared with every other; past this many, one sweep is cheaper.
    rebuild = escaped_.size() > kMaxRegrown;
  }
  if (rebuild) {
    grown_.resize(n);
    for (std::size_t i = 0; i < n; ++i) grown_[i] = boxes[i].expanded(keep_margin_);
    // Kept pairs do not depend on who moves now: a body may wake or fall asleep in place.
    all_moving_.assign(n, 1);
    findAll(grown_, all_moving_, kept_);
    ++rebuilds_;
  } else if (!escaped_.empty()) {
    regrow(boxes);
  }
  // A pair whose boxes overlap has overlapping grown boxes, so it is among the kept ones.
  for (const ProxyPair& p : kept_) {
    if (wanted(moving, p.first, p.second) && boxes[p.first].overlaps(boxes[p.second])) {
      out.push_back(p);
    }
  }
}

void Broadphase::regrow(std::span<const Aabb> boxes) {
  const auto n = static_cast<std::uint32_t>(boxes.size());
  is_escaped_.assign(n, 0);
  for (std::uint32_t e : escaped_) {
    is_escaped_[e] = 1;
    grown_[e] = boxes[e].expanded(keep_margin_);
  }
  std::erase_if(kept_, [&](const ProxyPair& p) {
    return is_escaped_[p.first] != 0 || is_escaped_[p.second] != 0;
  });
  fresh_.clear();
  for (std::uint32_t e : escaped_) {
    for (std::uint32_t j = 0; j < n; ++j) {
      // A pair of two escaped boxes is found once, from the lower index.
      if (j == e || (is_escaped_[j] && j < e) || !grown_[e].overlaps(grown_[j])) continue;
      fresh_.push_back(e < j ? ProxyPair{e, j} : ProxyPair{j, e});
    }
  }
  std::sort(fresh_.begin(), fresh_.end());
  pair_scratch_.resize(kept_.size() + fresh_.size());
  std::merge(kept_.begin(), kept_.end(), fresh_.begin(), fresh_.end(), pair_scratch_.begin());
  kept_.swap(pair_scratch_);
  regrown_ += escaped_.size();
}

void Broadphase::findAll(std::span<const Aabb> boxes, std::span<const std::uint8_t> moving,
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
  sortPairs(out, boxes.size(), pair_start_, pair_scratch_);
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
  // Sorted by (lower x, index), a strict order: the sweep order is the same however it is
  // reached. Last step's order is nearly sorted after a small step, so insertion sort from it
  // costs about n; a budget of moves falls back to std::sort when much has changed.
  const auto before = [&](std::uint32_t a, std::uint32_t b) {
    return boxes[a].lo.x() != boxes[b].lo.x() ? boxes[a].lo.x() < boxes[b].lo.x() : a < b;
  };
  if (order_.size() != n) {
    order_.resize(n);
    for (std::uint32_t i = 0; i < n; ++i) order_[i] = i;
    std::sort(order_.begin(), order_.end(), before);
  } else if (!insertionSort(order_, before, 8 * std::size_t(n))) {
    std::sort(order_.begin(), order_.end(), before);
  }
  // The sweep reads the boxes in sweep order from one contiguous copy.
  swept_.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) {
    const std::uint32_t i = order_[k];
    swept_[k] = {boxes[i], i, moving[i] != 0};
  }
  for (std::uint32_t k = 0; k < n; ++k) {
    const Swept& a = swept_[k];
    const double hi_x = a.box.hi.x();
    for (std::uint32_t m = k + 1; m < n; ++m) {
      const Swept& b = swept_[m];
      if (b.box.lo.x() > hi_x) break;
      if ((a.moving || b.moving) && a.box.overlaps(b.box)) {
        out.push_back(a.index < b.index ? ProxyPair{a.index, b.index}
                                        : ProxyPair{b.index, a.index});
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
