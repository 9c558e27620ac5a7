#pragma once
// A colony's trail as fixed-point integers, one per cell of the map: the trail of the zone's ant
// colonies (zone_node/systems/ant_movement.h), which ants on every rank read and lay. Integers
// make the trail independent of how the ants are split over ranks: each rank adds up its own
// ants' deposits of a tick, the sum of every rank's deltas is exact and order-free, and
// evaporateAndAdd() is integer arithmetic, alike on every rank. Evaporation happens per tick;
// the library AntColony (crowd/ant_colony.h) keeps double trails per directed step instead.

#include <cstdint>
#include <span>
#include <vector>

#include "ai/grid_map.h"

namespace zonesim::crowd {

/// Trail units per unit of pheromone (fixed point).
inline constexpr double kTrailScale = double(1 << 20);

/// Trail units an ant lays on one cell for a route of `length` (m): deposit / length, at least
/// one unit, so that every trip leaves a mark however long it was.
std::int64_t trailDepositUnits(double deposit, double length);

/// One colony's trail over every cell of a map.
class AntTrail {
 public:
  /// `initial` pheromone on every cell of `map` (which must outlive it; at least one unit), of
  /// which a fraction `evaporation` is lost per second, in ticks of `dt` s.
  AntTrail(const ai::GridMap& map, double initial, double evaporation, double dt);

  /// Number of cells (the size of the deltas that evaporateAndAdd() takes).
  std::size_t size() const { return units_.size(); }
  /// Index of cell c in the trail and in the deltas.
  std::size_t index(ai::Cell c) const { return std::size_t(map_.index(c.x, c.y)); }
  /// Trail on cell c, in units.
  std::int64_t units(ai::Cell c) const { return units_[index(c)]; }
  /// Trail on cell c, in pheromone.
  double at(ai::Cell c) const { return double(units_[index(c)]) / kTrailScale; }
  /// Sum of the trail over the map, in pheromone.
  double total() const;
  /// Fraction of the trail kept per tick, as 32.32 fixed point.
  std::uint64_t keep() const { return keep_; }

  /// Evaporates every cell by one tick (rounding down, never below one unit) and adds its
  /// delta (one per cell, in units: every rank's deposits of the tick, summed).
  void evaporateAndAdd(std::span<const std::int64_t> deltas);
  /// The preferred route from `nest` to `food`: always the strongest unvisited neighbour
  /// (crowd/ant_step.h's strongestTrailRoute); empty when it dead-ends before the food.
  std::vector<ai::Cell> strongestRoute(ai::Cell nest, ai::Cell food) const;

 private:
  const ai::GridMap& map_;
  std::vector<std::int64_t> units_;
  std::uint64_t keep_ = 0;
};

}  // namespace zonesim::crowd
