#pragma once
// The round-trip estimate of RFC 6298, shared by the gateway's state resends (wire/ack_window.h)
// and the reliable stream (wire/reliable_stream.h): smoothed RTT and its mean deviation from
// each sample, and a retransmission timeout of SRTT + 4 RTTVAR within bounds.

#include <algorithm>
#include <cmath>

namespace zonesim::gateway {

class RttEstimator {
 public:
  /// One round trip, seconds (negative ones, from clocks that stepped, count as 0).
  void sample(double rtt_s) {
    double r = std::max(0.0, rtt_s);
    if (srtt_s_ < 0) {
      srtt_s_ = r;
      rttvar_s_ = r / 2;
    } else {
      rttvar_s_ = 0.75 * rttvar_s_ + 0.25 * std::abs(srtt_s_ - r);
      srtt_s_ = 0.875 * srtt_s_ + 0.125 * r;
    }
  }
  bool sampled() const { return srtt_s_ >= 0; }
  /// The smoothed round trip, seconds (negative before any sample).
  double srttS() const { return srtt_s_; }
  /// SRTT + 4 RTTVAR within [min_s, max_s]; before any sample, unsampled_s (also bounded).
  double rtoS(double min_s, double max_s, double unsampled_s) const {
    return std::clamp(sampled() ? srtt_s_ + 4 * rttvar_s_ : unsampled_s, min_s, max_s);
  }

 private:
  double srtt_s_ = -1, rttvar_s_ = 0;  // srtt < 0: no sample yet
};

}  // namespace zonesim::gateway
