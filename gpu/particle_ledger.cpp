#include "gpu/particle_ledger.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

namespace zonesim::gpu {

std::uint32_t toMicros(double seconds, const char* what) {
  if (!std::isfinite(seconds) || seconds <= 0.0 || seconds > kMaxMicrosSeconds) {
    throw std::invalid_argument(std::string(what) + " must be in (0, " +
                                std::to_string(kMaxMicrosSeconds) + "] seconds, not " +
                                std::to_string(seconds));
  }
  double micros = std::round(seconds * 1e6);
  return micros < 1.0 ? 1u : std::uint32_t(micros);
}

ParticleLedger::ParticleLedger(std::size_t max_slots) : max_slots_(max_slots) {
  if (max_slots == 0 || max_slots > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("max particles must be in [1, 2^32 - 1], not " +
                                std::to_string(max_slots));
  }
}

bool ParticleLedger::allocate(std::uint32_t life_us, std::uint32_t& slot) {
  if (!free_.empty()) {
    std::pop_heap(free_.begin(), free_.end(), std::greater<>());
    slot = free_.back();
    free_.pop_back();
  } else if (expiry_us_.size() < max_slots_) {
    slot = std::uint32_t(expiry_us_.size());
    expiry_us_.push_back(0);
  } else {
    return false;
  }
  expiry_us_[slot] = now_us_ + life_us;
  expiries_.emplace_back(expiry_us_[slot], slot);
  std::push_heap(expiries_.begin(), expiries_.end(), std::greater<>());
  ++alive_;
  return true;
}

void ParticleLedger::advance(std::uint32_t dt_us) {
  now_us_ += dt_us;
  while (!expiries_.empty() && expiries_.front().first <= now_us_) {
    std::pop_heap(expiries_.begin(), expiries_.end(), std::greater<>());
    free_.push_back(expiries_.back().second);
    std::push_heap(free_.begin(), free_.end(), std::greater<>());
    expiries_.pop_back();
    --alive_;
  }
}

void ParticleLedger::reserve(std::size_t slots) {
  slots = std::min(slots, max_slots_);
  expiry_us_.reserve(slots);
  expiries_.reserve(slots);
  free_.reserve(slots);
}

}  // namespace zonesim::gpu
