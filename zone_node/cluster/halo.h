#pragma once
// Ghost copies of neighbours' entities within the halo width (LAMMPS' borders + forward_comm).
// borders(): decide, per local entity, which ranks' zones lie within width + skin of it, and
// keep those send lists. forward(): every tick, send the current state of every listed entity
// and replace the ghosts. The lists are rebuilt only when they may be stale: this rank's set of
// entities changed (migration, creation, removal), the zone boundaries moved, or some entity
// moved more than skin/2 since the lists were built (LAMMPS' neighbour-list skin rule).

#include <mpi.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "common/entity_id.h"
#include "zone_node/cluster/byte_exchange.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"
#include "zone_node/zone_layout.h"

namespace zonesim::zone {

/// What one refresh did.
struct HaloStats {
  std::uint64_t ghosts = 0;      ///< ghosts held after the refresh
  std::uint64_t sent = 0;        ///< entity copies sent
  std::uint64_t bytes_sent = 0;  ///< payload bytes sent
  bool rebuilt = false;          ///< send lists were rebuilt this tick
};

class HaloExchange {
 public:
  /// width: the widest interaction radius the systems need; skin: slack that lets send lists
  /// survive several ticks of motion.
  HaloExchange(MPI_Comm comm, int rank, int size, double width, double skin);

  /// Refreshes the ghosts from the neighbours (collective). `layout_version` changes whenever
  /// zone boundaries move.
  HaloStats refresh(const EntityStore& store, const ZoneLayout& layout,
                    std::uint64_t layout_version);
  const GhostStore& ghosts() const { return ghosts_; }
  /// Sends `column` with every ghost from now on (GhostStore::addColumn); every rank must
  /// register the same columns in the same order, before the first refresh.
  std::size_t addColumn(GhostColumn column) { return ghosts_.addColumn(std::move(column)); }
  double width() const { return width_; }

 private:
  bool listsStale(const EntityStore& store, std::uint64_t layout_version) const;
  void borders(const EntityStore& store, const ZoneLayout& layout);

  int rank_, size_;
  double width_, skin_;
  ByteExchange bytes_;
  GhostStore ghosts_;
  // Send lists by id (store indices move when entities come and go), per destination rank.
  std::vector<std::vector<EntityId>> send_;
  std::vector<EntityId> built_ids_;  // the store's ids when the lists were built, by index
  std::vector<Vec3> built_pos_;      // and their positions
  std::uint64_t built_layout_ = ~0ull;
  bool built_ = false;
  std::vector<std::vector<std::int64_t>> column_values_;  // this refresh's, per column, by index
};

}  // namespace zonesim::zone
