#pragma once
// Dynamic load balancing: every K ticks the ranks share what their own work cost them (one
// allgather); when the slowest rank costs more than `threshold` times the mean, zone boundaries
// move part of the way toward equal cost. Hysteresis: once started, balancing continues until
// the imbalance falls below the midpoint between 1 and the threshold, so boundaries neither
// thrash around the threshold nor stop halfway. Every rank computes the same new layout from
// the same numbers; entities then follow through ordinary migration.

#include <mpi.h>

#include <cstdint>
#include <vector>

#include "zone_node/zone_layout.h"

namespace zonesim::zone {

struct BalanceSettings {
  int every = 0;            ///< ticks between balance checks; 0 = never
  double threshold = 1.25;  ///< max/mean cost that starts balancing
  double step = 0.5;        ///< fraction of the way boundaries move per check
  double min_width = 1.0;   ///< no zone narrower than this (metres)
};

class LoadBalancer {
 public:
  LoadBalancer(MPI_Comm comm, const BalanceSettings& settings);

  /// Adds the seconds this rank spent on its own work this tick.
  void record(double seconds) { cost_ += seconds; }
  /// Collective on check ticks (tick % every == 0): may move the layout's boundaries.
  /// Returns true when it did.
  bool check(std::uint64_t tick, ZoneLayout& layout);
  /// max/mean of the last check's costs (1 = balanced).
  double imbalance() const { return imbalance_; }

 private:
  MPI_Comm comm_;
  BalanceSettings settings_;
  double cost_ = 0;
  double imbalance_ = 1;
  bool active_ = false;
  std::vector<double> costs_;
};

/// max/mean of costs (1 for all-equal or all-zero).
double imbalanceOf(const std::vector<double>& costs);

/// The hysteresis: whether balancing is on after a check that measured `imbalance`.
bool balancingActive(bool was_active, double imbalance, double threshold);

}  // namespace zonesim::zone
