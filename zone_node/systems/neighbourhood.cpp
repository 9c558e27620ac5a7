#include "zone_node/systems/neighbourhood.h"

#include <algorithm>
#include <cmath>

#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"

namespace zonesim::zone {

namespace {
// The same rule for own entities and ghosts (which carry no avatar data), so the neighbours
// found do not depend on which zone owns a flyer.
bool isWalker(EntityKind k, const Vec3& pos, double air) {
  return k == EntityKind::Npc || (k == EntityKind::Avatar && pos.y() <= air);
}
}  // namespace

std::int64_t Neighbourhood::cellKey(double x, double z) const {
  auto cx =
      std::clamp<std::int64_t>(std::int64_t(std::floor((x - origin_x_) / cell_)), 0, columns_ - 1);
  auto cz =
      std::clamp<std::int64_t>(std::int64_t(std::floor((z - origin_z_) / cell_)), 0, rows_ - 1);
  return cz * columns_ + cx;
}

void Neighbourhood::build(const EntityStore& store, const GhostStore* ghosts, double radius,
                          double air) {
  std::vector<Neighbour> all;
  all.reserve(store.size() + (ghosts ? ghosts->size() : 0));
  for (std::size_t i = 0; i < store.size(); ++i)
    if (isWalker(store.kind[i], store.pos[i], air))
      all.push_back({store.id[i], store.pos[i], store.vel[i]});
  if (ghosts)
    for (std::size_t i = 0; i < ghosts->size(); ++i)
      if (isWalker(ghosts->kind[i], ghosts->pos[i], air))
        all.push_back({ghosts->id[i], ghosts->pos[i], ghosts->vel[i]});
  points_.clear();
  cell_start_.assign(2, 0);
  if (all.empty() || !(radius > 0)) return;

  double min_x = all[0].pos.x(), max_x = min_x, min_z = all[0].pos.z(), max_z = min_z;
  for (const Neighbour& n : all) {
    min_x = std::min(min_x, n.pos.x());
    max_x = std::max(max_x, n.pos.x());
    min_z = std::min(min_z, n.pos.z());
    max_z = std::max(max_z, n.pos.z());
  }
  cell_ = radius;
  origin_x_ = min_x;
  origin_z_ = min_z;
  // Bounded cell count: a sparse, huge region still gets a grid of at most ~4 cells per point.
  double limit = std::sqrt(4.0 * double(all.size())) + 1;
  columns_ = std::clamp<std::int64_t>(std::int64_t((max_x - min_x) / cell_) + 1, 1, 1 << 20);
  rows_ = std::clamp<std::int64_t>(std::int64_t((max_z - min_z) / cell_) + 1, 1, 1 << 20);
  while (double(columns_) * double(rows_) > limit * limit) {
    cell_ *= 2;
    columns_ = std::int64_t((max_x - min_x) / cell_) + 1;
    rows_ = std::int64_t((max_z - min_z) / cell_) + 1;
  }
  // Counting sort by cell.
  std::size_t cells = std::size_t(columns_ * rows_);
  cell_start_.assign(cells + 1, 0);
  std::vector<std::int64_t> key(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    key[i] = cellKey(all[i].pos.x(), all[i].pos.z());
    ++cell_start_[std::size_t(key[i]) + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  points_.resize(all.size());
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < all.size(); ++i) points_[fill[std::size_t(key[i])]++] = all[i];
}

void Neighbourhood::query(const Vec3& p, double radius, EntityId self,
                          std::vector<Neighbour>& out) const {
  out.clear();
  if (points_.empty()) return;
  const double r2 = radius * radius;
  std::int64_t x0 =
      std::max<std::int64_t>(0, std::int64_t(std::floor((p.x() - radius - origin_x_) / cell_)));
  std::int64_t x1 = std::min<std::int64_t>(
      columns_ - 1, std::int64_t(std::floor((p.x() + radius - origin_x_) / cell_)));
  std::int64_t z0 =
      std::max<std::int64_t>(0, std::int64_t(std::floor((p.z() - radius - origin_z_) / cell_)));
  std::int64_t z1 = std::min<std::int64_t>(
      rows_ - 1, std::int64_t(std::floor((p.z() + radius - origin_z_) / cell_)));
  for (std::int64_t cz = z0; cz <= z1; ++cz) {
    for (std::int64_t cx = x0; cx <= x1; ++cx) {
      std::size_t c = std::size_t(cz * columns_ + cx);
      for (std::uint32_t k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
        const Neighbour& n = points_[k];
        if (n.id == self) continue;
        double dx = n.pos.x() - p.x(), dz = n.pos.z() - p.z();
        if (dx * dx + dz * dz <= r2) out.push_back(n);
      }
    }
  }
  std::sort(out.begin(), out.end(),
            [](const Neighbour& a, const Neighbour& b) { return a.id < b.id; });
}

}  // namespace zonesim::zone
