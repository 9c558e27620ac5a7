#pragma once
// The world cache's entities predicted to one sim time and bucketed by the cell of that
// predicted position. Built once a gateway tick, so that each player's visibility scan reads
// flat arrays instead of hash maps, no entity is extrapolated once per player, and a scan reads
// exactly the cells that meet its disc (an entity that moved on from the cell its zone sampled
// it in is found where it is now).

#include <cstdint>
#include <span>
#include <vector>

namespace zonesim {
class InterestGrid;
}  // namespace zonesim

namespace zonesim::gateway {

class WorldCache;

/// One entity as visibility needs it.
struct SnapEntity {
  std::uint64_t id = 0;
  std::uint64_t version = 0;  ///< the cache's version of its state
  double x = 0, z = 0;        ///< where its own model puts it at the snapshot's time
  std::uint8_t kind = 0;
};

class WorldSnapshot {
 public:
  /// Predicts every cached entity to sim_now and files it under the grid cell of that position
  /// (clamped into the grid). Reuses its storage: no allocation once warm.
  void rebuild(const WorldCache& cache, const InterestGrid& grid, double sim_now);
  /// The entities predicted to be in `cell` (empty for a cell out of range).
  std::span<const SnapEntity> cell(int cell) const;
  /// Those of them whose state changed since the previous rebuild (a new version): the same
  /// list for every player who sees the cell, so a player's tick between full visibility scans
  /// reads only what changed (selectChanged).
  std::span<const SnapEntity> changedIn(int cell) const;
  /// The sim time positions were predicted to.
  double simNow() const { return sim_now_; }
  std::size_t size() const { return all_.entities.size(); }

 private:
  struct Placed {
    SnapEntity entity;
    int cell;
  };
  // Entities grouped by cell: cell c holds [begin[c], begin[c + 1]).
  struct ByCell {
    std::vector<SnapEntity> entities;
    std::vector<std::uint32_t> begin;
    std::vector<std::uint32_t> fill;  // next free slot per cell, while filing
    /// Files the placed entities that pass keep(), by cell (a counting sort).
    template <typename Keep>
    void file(const std::vector<Placed>& placed, int cells, Keep keep);
    std::span<const SnapEntity> of(int cell) const;
  };
  std::vector<Placed> predicted_;  // while rebuilding: in the cache's order
  ByCell all_, changed_;
  std::uint64_t seen_version_ = 0;  // the cache's newest version at the previous rebuild
  double sim_now_ = 0;
};

}  // namespace zonesim::gateway
