#include "zone_node/zone_layout.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace zonesim::zone {

namespace {
std::vector<double> evenSplits(double lo, double hi, int n) {
  std::vector<double> s(n + 1);
  for (int i = 0; i <= n; ++i) s[i] = lo + (hi - lo) * double(i) / double(n);
  s[n] = hi;
  return s;
}

int slot(const std::vector<double>& splits, double v) {
  // upper_bound over the interior edges: the first edge greater than v closes v's slot.
  auto it = std::upper_bound(splits.begin() + 1, splits.end() - 1, v);
  return int(it - (splits.begin() + 1));
}
}  // namespace

ZoneLayout::ZoneLayout(const SceneBox& world, int columns, int rows)
    : columns_(columns),
      rows_(rows),
      x_splits_(evenSplits(world.min.x, world.max.x, columns)),
      z_splits_(evenSplits(world.min.z, world.max.z, rows)) {
  if (columns < 1 || rows < 1) throw std::invalid_argument("zone grid needs at least 1x1");
}

ZoneLayout ZoneLayout::forRanks(const Scene& scene, int ranks) {
  if (scene.zones.columns * scene.zones.rows == ranks)
    return ZoneLayout(scene.world, scene.zones.columns, scene.zones.rows);
  int rows = int(std::sqrt(double(ranks)));
  while (ranks % rows != 0) --rows;
  return ZoneLayout(scene.world, ranks / rows, rows);
}

ZoneRect ZoneLayout::rect(int rank) const {
  int c = rank % columns_, r = rank / columns_;
  return {x_splits_[c], z_splits_[r], x_splits_[c + 1], z_splits_[r + 1]};
}

int ZoneLayout::ownerOf(double x, double z) const {
  return slot(z_splits_, z) * columns_ + slot(x_splits_, x);
}

}  // namespace zonesim::zone
