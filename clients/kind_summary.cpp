#include "clients/kind_summary.h"

#include <algorithm>

#include "common/metrics.h"
#include "common/stats.h"

namespace zonesim::clients {

std::string kindsSummaryJson(const std::vector<std::unique_ptr<SimPlayer>>& players,
                             double duration_s) {
  JsonLine all;
  for (std::size_t k = 0; k < kPlayerKindCount; ++k) {
    std::vector<double> kbps;
    Reservoir error;  // merge() appends every player's samples and keeps the largest error
    double visible = 0;
    for (const auto& p : players) {
      if (std::size_t(p->kind()) != k) continue;
      double s = duration_s > 0 ? duration_s : 1;
      kbps.push_back(double(p->counters().bytes_in) * 8.0 / 1000.0 / s);
      error.merge(p->counters().dr_error_m);
      visible += p->meanVisible();
    }
    if (kbps.empty()) continue;
    JsonLine j;
    j.add("players", std::uint64_t(kbps.size()))
        .add("kbps_in_p50", percentile(kbps, 50))
        .add("kbps_in_max", *std::max_element(kbps.begin(), kbps.end()))
        .add("dr_error_m_p50", percentile(error.samples(), 50))
        .add("dr_error_m_p99", percentile(error.samples(), 99))
        .add("dr_error_m_max", error.max())
        .add("visible_entities_mean", visible / double(kbps.size()));
    all.addRaw(kPlayerKindNames[k], j.str());
  }
  return all.str();
}

}  // namespace zonesim::clients
