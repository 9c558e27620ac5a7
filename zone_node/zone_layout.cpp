#include "zone_node/zone_layout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/scene.h"
#include "zone_node/population.h"

namespace zonesim::zone {

namespace {

std::vector<double> evenSplits(double lo, double hi, int n) {
  std::vector<double> s(std::size_t(n) + 1);
  for (int i = 0; i <= n; ++i) s[std::size_t(i)] = lo + (hi - lo) * double(i) / double(n);
  s.back() = hi;
  return s;
}

int slot(const std::vector<double>& splits, double v) {
  // upper_bound over the interior edges: the first edge greater than v closes v's slot.
  auto it = std::upper_bound(splits.begin() + 1, splits.end() - 1, v);
  return int(it - (splits.begin() + 1));
}

/// Splits where the piecewise-linear cumulative cost reaches equal shares; costs[i] is spread
/// evenly over [splits[i], splits[i+1]].
std::vector<double> equalCostSplits(const std::vector<double>& splits,
                                    const std::vector<double>& costs) {
  std::size_t n = costs.size();
  double total = 0;
  for (double c : costs) total += c;
  std::vector<double> out = splits;
  if (total <= 0) return out;
  std::size_t seg = 0;
  double before = 0;  // cost of the segments left of seg
  for (std::size_t i = 1; i < n; ++i) {
    double target = total * double(i) / double(n);
    while (seg + 1 < n && before + costs[seg] < target) before += costs[seg++];
    double width = splits[seg + 1] - splits[seg];
    double f = costs[seg] > 0 ? (target - before) / costs[seg] : 0.5;
    out[i] = splits[seg] + std::clamp(f, 0.0, 1.0) * width;
  }
  return out;
}

/// Moves interior edges step of the way to target, then keeps every slot at least min_width.
void relax(std::vector<double>& splits, const std::vector<double>& target, double step,
           double min_width) {
  std::size_t n = splits.size() - 1;
  double lo = splits.front(), hi = splits.back();
  min_width = std::min(min_width, (hi - lo) / double(n));
  for (std::size_t i = 1; i < n; ++i) splits[i] += step * (target[i] - splits[i]);
  for (std::size_t i = 1; i < n; ++i) {
    double min_here = splits[i - 1] + min_width;
    double max_here = hi - double(n - i) * min_width;
    splits[i] = std::clamp(splits[i], min_here, max_here);
  }
}

/// Edges at the quantiles of sorted values, n slots between lo and hi.
std::vector<double> quantileSplits(std::vector<double> values, double lo, double hi, int n) {
  std::vector<double> s = evenSplits(lo, hi, n);
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  for (int i = 1; i < n; ++i) {
    std::size_t k = values.size() * std::size_t(i) / std::size_t(n);
    // Halfway between neighbours, so no point sits exactly on an edge.
    double a = values[std::min(k, values.size() - 1)];
    double b = k > 0 ? values[k - 1] : lo;
    s[std::size_t(i)] = std::clamp(0.5 * (a + b), lo, hi);
  }
  for (int i = 1; i < n; ++i)
    s[std::size_t(i)] = std::max(s[std::size_t(i)], s[std::size_t(i) - 1]);
  return s;
}

}  // namespace

ZoneLayout::ZoneLayout(const SceneBox& world, int columns, int rows)
    : columns_(columns), rows_(rows) {
  if (columns < 1 || rows < 1) throw std::invalid_argument("zone grid needs at least 1x1");
  x_splits_ = evenSplits(world.min.x, world.max.x, columns);
  z_splits_.assign(std::size_t(columns), evenSplits(world.min.z, world.max.z, rows));
}

ZoneLayout ZoneLayout::forRanks(const Scene& scene, int ranks) {
  int columns = scene.zones.columns, rows = scene.zones.rows;
  if (columns * rows != ranks) {
    rows = int(std::sqrt(double(ranks)));
    while (ranks % rows != 0) --rows;
    columns = ranks / rows;
  }
  ZoneLayout layout(scene.world, columns, rows);
  if (scene.zones.kind == SceneZones::Kind::Rcb) {
    std::vector<std::pair<double, double>> points;
    forEachInitialEntity(
        scene, [&](const EntityRecordData& r) { points.emplace_back(r.pos.x(), r.pos.z()); });
    layout.bisect(points);
  }
  return layout;
}

ZoneRect ZoneLayout::rect(int rank) const {
  int c = rank % columns_, r = rank / columns_;
  const std::vector<double>& z = z_splits_[std::size_t(c)];
  return {x_splits_[std::size_t(c)], z[std::size_t(r)], x_splits_[std::size_t(c) + 1],
          z[std::size_t(r) + 1]};
}

int ZoneLayout::ownerOf(double x, double z) const {
  int c = slot(x_splits_, x);
  return slot(z_splits_[std::size_t(c)], z) * columns_ + c;
}

void ZoneLayout::bisect(std::span<const std::pair<double, double>> points) {
  std::vector<double> xs;
  for (const auto& p : points) xs.push_back(p.first);
  x_splits_ = quantileSplits(xs, x_splits_.front(), x_splits_.back(), columns_);
  double z_lo = z_splits_[0].front(), z_hi = z_splits_[0].back();
  for (int c = 0; c < columns_; ++c) {
    std::vector<double> zs;
    for (const auto& p : points)
      if (slot(x_splits_, p.first) == c) zs.push_back(p.second);
    z_splits_[std::size_t(c)] = quantileSplits(zs, z_lo, z_hi, rows_);
  }
}

void ZoneLayout::rebalance(std::span<const double> cost, double step, double min_width) {
  std::vector<double> column_cost(std::size_t(columns_), 0.0);
  for (int r = 0; r < zoneCount(); ++r)
    column_cost[std::size_t(r % columns_)] += cost[std::size_t(r)];
  relax(x_splits_, equalCostSplits(x_splits_, column_cost), step, min_width);
  for (int c = 0; c < columns_; ++c) {
    std::vector<double> row_cost(static_cast<std::size_t>(rows_));
    for (int r = 0; r < rows_; ++r) row_cost[std::size_t(r)] = cost[std::size_t(r * columns_ + c)];
    std::vector<double>& z = z_splits_[std::size_t(c)];
    relax(z, equalCostSplits(z, row_cost), step, min_width);
  }
}

}  // namespace zonesim::zone
