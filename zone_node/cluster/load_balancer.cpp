#include "zone_node/cluster/load_balancer.h"

#include <algorithm>
#include <numeric>

namespace zonesim::zone {

double imbalanceOf(const std::vector<double>& costs) {
  if (costs.empty()) return 1;
  double mean = std::accumulate(costs.begin(), costs.end(), 0.0) / double(costs.size());
  return mean > 0 ? *std::max_element(costs.begin(), costs.end()) / mean : 1.0;
}

bool balancingActive(bool was_active, double imbalance, double threshold) {
  double release = 1.0 + 0.5 * (threshold - 1.0);
  return was_active ? imbalance > release : imbalance > threshold;
}

LoadBalancer::LoadBalancer(MPI_Comm comm, const BalanceSettings& settings)
    : comm_(comm), settings_(settings) {
  int size = 1;
  MPI_Comm_size(comm_, &size);
  costs_.resize(std::size_t(size));
}

bool LoadBalancer::check(std::uint64_t tick, ZoneLayout& layout) {
  if (settings_.every <= 0 || tick % std::uint64_t(settings_.every) != 0) return false;
  MPI_Allgather(&cost_, 1, MPI_DOUBLE, costs_.data(), 1, MPI_DOUBLE, comm_);
  cost_ = 0;
  imbalance_ = imbalanceOf(costs_);
  active_ = balancingActive(active_, imbalance_, settings_.threshold);
  if (!active_ || costs_.size() < 2) return false;
  layout.rebalance(costs_, settings_.step, settings_.min_width);
  return true;
}

}  // namespace zonesim::zone
