#include "wire/link_model.h"

#include <algorithm>
#include <cmath>

namespace zonesim::gateway {

LinkCounters& LinkCounters::operator+=(const LinkCounters& o) {
  offered += o.offered;
  lost += o.lost;
  tail_dropped += o.tail_dropped;
  reordered += o.reordered;
  duplicated += o.duplicated;
  corrupted += o.corrupted;
  delivered += o.delivered;
  return *this;
}

LinkModel::LinkModel(const LinkProfile& profile, std::uint64_t seed, std::uint64_t stream)
    : profile_(profile), rng_(seed, stream) {
  validateLinkProfile(profile_);
  pareto_scale_ms_ = profile_.jitter_ms * (profile_.pareto_shape - 1);
}

double LinkModel::normal() {
  // Box–Muller; 1 - u keeps the logarithm finite.
  double u = 1 - rng_.uniform(), v = rng_.uniform();
  return std::sqrt(-2 * std::log(u)) * std::cos(2 * M_PI * v);
}

double LinkModel::sampleDelayMs() {
  const LinkProfile& p = profile_;
  switch (p.jitter) {
    case JitterShape::None:
      return p.delay_ms;
    case JitterShape::Uniform:
      return p.delay_ms + rng_.uniform(0, p.jitter_ms);
    case JitterShape::Normal:
      return std::max(0.0, p.delay_ms + p.jitter_ms * normal());
    case JitterShape::Pareto:  // Lomax (Pareto II) by inversion: scale ((1-u)^(-1/a) - 1)
      return p.delay_ms +
             pareto_scale_ms_ * (std::pow(1 - rng_.uniform(), -1 / p.pareto_shape) - 1);
  }
  return p.delay_ms;
}

bool LinkModel::lose() {
  const LinkProfile& p = profile_;
  double loss = bad_ ? p.loss_bad : p.loss_good;
  bool lost = loss > 0 && rng_.uniform() < loss;
  if (p.ge_p > 0) bad_ = bad_ ? rng_.uniform() >= p.ge_r : rng_.uniform() < p.ge_p;
  return lost;
}

Fate LinkModel::offer(std::size_t bytes, std::int64_t now_ns) {
  const LinkProfile& p = profile_;
  ++counters_.offered;
  Fate fate;
  if (lose()) {
    ++counters_.lost;
    return fate;
  }
  std::int64_t leave_ns = now_ns;
  if (p.rate_kbps > 0) {
    double ns_per_byte = 8e6 / p.rate_kbps;
    // Bytes still waiting (the one on the wire included) when this one arrives.
    double backlog = double(std::max<std::int64_t>(0, busy_until_ns_ - now_ns)) / ns_per_byte;
    if (backlog + double(bytes) > double(p.queue_bytes)) {
      ++counters_.tail_dropped;
      return fate;
    }
    busy_until_ns_ = std::max(busy_until_ns_, now_ns) + std::int64_t(double(bytes) * ns_per_byte);
    leave_ns = busy_until_ns_;
  }
  std::int64_t due = leave_ns + std::int64_t(sampleDelayMs() * 1e6);
  if (p.reorder > 0 && rng_.uniform() < p.reorder) {
    // Held aside: it neither waits for the FIFO floor nor raises it, so later ones overtake.
    due += std::int64_t(p.reorder_gap_ms * 1e6);
    ++counters_.reordered;
  } else if (p.keep_order) {
    due = std::max(due, last_due_ns_);
    last_due_ns_ = due;
  }
  fate.copies = 1;
  fate.delivery[0].due_ns = due;
  if (p.duplicate > 0 && rng_.uniform() < p.duplicate) {
    fate.copies = 2;
    fate.delivery[1].due_ns = due;
    ++counters_.duplicated;
  }
  for (int c = 0; c < fate.copies; ++c)
    if (p.corrupt > 0 && bytes > 0 && rng_.uniform() < p.corrupt) {
      fate.delivery[std::size_t(c)].flip_bit = std::int64_t(rng_.next() % (bytes * 8));
      ++counters_.corrupted;
    }
  counters_.delivered += std::uint64_t(fate.copies);
  return fate;
}

}  // namespace zonesim::gateway
