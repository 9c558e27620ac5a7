#pragma once
// The gateway's estimate of the zones' simulation clock: the newest sim_time seen in any sample,
// advanced by wall time since it arrived. States are extrapolated to this time before they go to
// a client, so a Spawn of an entity last updated seconds ago still shows it where it is now.
// Under time dilation (zone_node/time_dilation.h) the zones' samples carry the factor their
// ticks run at, and the clock runs on at that rate.

#include <algorithm>
#include <cstdint>

namespace zonesim::gateway {

class ZoneClock {
 public:
  /// sim_per_wall: simulated seconds per wall second (scene tick_rate * dt).
  explicit ZoneClock(double sim_per_wall) : sim_per_wall_(sim_per_wall) {}

  /// Records a sample's tick, sim_time and time dilation factor as seen at now_ns.
  void observe(std::uint64_t tick, double sim_time, double dilation, std::int64_t now_ns) {
    if (sim_time <= latest_sim_) return;
    // A factor outside (0, 1] is no zone's (a zone without dilation says 1): full speed.
    dilation_ = dilation > 0 && dilation <= 1 ? dilation : 1.0;
    min_dilation_ = std::min(min_dilation_, dilation_);
    latest_sim_ = sim_time;
    latest_tick_ = tick;
    anchor_ns_ = now_ns;
    seen_ = true;
  }

  /// Estimated zone sim time at now_ns; the extrapolation is capped so that zones that stopped
  /// do not make the gateway invent motion forever.
  double simNow(std::int64_t now_ns) const {
    if (!seen_) return 0;
    double wall = std::clamp(double(now_ns - anchor_ns_) * 1e-9, 0.0, kMaxExtrapolationSeconds);
    return latest_sim_ + wall * sim_per_wall_ * dilation_;
  }

  /// The zones' time dilation factor of the newest sample (1 before any).
  double dilation() const { return dilation_; }
  /// The lowest factor seen so far.
  double minDilation() const { return min_dilation_; }

  /// Newest zone tick seen (0 before any sample).
  std::uint64_t tick() const { return latest_tick_; }

 private:
  static constexpr double kMaxExtrapolationSeconds = 1.0;
  double sim_per_wall_;
  double latest_sim_ = 0;
  double dilation_ = 1;
  double min_dilation_ = 1;
  std::uint64_t latest_tick_ = 0;
  std::int64_t anchor_ns_ = 0;
  bool seen_ = false;
};

}  // namespace zonesim::gateway
