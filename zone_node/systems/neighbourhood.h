#pragma once
// Who is near whom on the ground plane, over this zone's walkers and the ghosts of its
// neighbours' walkers alike: a uniform grid with cells as wide as the query radius. Results
// come sorted by entity id, so sums over neighbours are done in the same order on every
// decomposition and a zone's result does not depend on where its neighbours live.

#include <cstdint>
#include <limits>
#include <vector>

#include "common/entity_id.h"
#include "common/math.h"

namespace zonesim::zone {

class EntityStore;
class GhostStore;

/// One neighbour found by a query.
struct Neighbour {
  EntityId id;
  Vec3 pos;
  Vec3 vel;
};

class Neighbourhood {
 public:
  /// Indexes the walkers (NPCs and avatars) of the store and of the ghosts, for queries of
  /// at most `radius`. Avatars higher than `air` (world y) are flying, not walking: nobody on
  /// the ground makes way for them.
  void build(const EntityStore& store, const GhostStore* ghosts, double radius,
             double air = std::numeric_limits<double>::infinity());
  /// Every indexed walker within `radius` (<= the build radius) of p on the ground plane,
  /// except `self`, in ascending id order.
  void query(const Vec3& p, double radius, EntityId self, std::vector<Neighbour>& out) const;
  std::size_t size() const { return points_.size(); }

 private:
  std::int64_t cellKey(double x, double z) const;

  double cell_ = 1;
  double origin_x_ = 0, origin_z_ = 0;
  std::int64_t columns_ = 1, rows_ = 1;
  std::vector<Neighbour> points_;          // sorted by cell
  std::vector<std::uint32_t> cell_start_;  // CSR: points_ of cell c are [start[c], start[c+1])
};

}  // namespace zonesim::zone
