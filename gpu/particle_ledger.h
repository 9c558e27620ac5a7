#pragma once
// Which particle slots are alive, kept on the host for both backends. Lifetimes are whole
// microseconds counted down by whole-microsecond steps: integer arithmetic gives the device's
// countdown and this ledger the same answer exactly, so emit can recycle dead slots without
// reading anything back, and both backends agree on every alive count.

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace zonesim::gpu {

/// The longest lifetime or step a uint32 microsecond count holds (about 71 minutes).
inline constexpr double kMaxMicrosSeconds = 4294.0;

/// seconds rounded to whole microseconds, at least 1; throws std::invalid_argument outside
/// (0, kMaxMicrosSeconds] or when not finite. what names the quantity in the message.
std::uint32_t toMicros(double seconds, const char* what);

class ParticleLedger {
 public:
  /// Never hands out more than max_slots slots.
  explicit ParticleLedger(std::size_t max_slots);

  /// A slot for a particle living life_us: the lowest dead slot, else a new one; returns
  /// false when all max_slots are alive.
  bool allocate(std::uint32_t life_us, std::uint32_t& slot);
  /// Advances time by dt_us and retires every particle whose life has run out.
  void advance(std::uint32_t dt_us);
  /// Reserves bookkeeping for slots slots, so that emits up to there do not allocate.
  void reserve(std::size_t slots);

  /// True when slot holds a live particle.
  bool alive(std::size_t slot) const {
    return slot < expiry_us_.size() && expiry_us_[slot] > now_us_;
  }
  /// Live particles.
  std::size_t aliveCount() const { return alive_; }
  /// Slots ever used (the high-water mark): the extent the device must step.
  std::size_t slotCount() const { return expiry_us_.size(); }
  /// The most slots this ledger hands out.
  std::size_t maxSlots() const { return max_slots_; }

 private:
  using Expiry = std::pair<std::uint64_t, std::uint32_t>;

  std::size_t max_slots_;
  std::uint64_t now_us_ = 0;
  std::size_t alive_ = 0;
  // Per slot: alive while expiry > now. 64-bit so the clock never wraps.
  std::vector<std::uint64_t> expiry_us_;
  // Min-heap (std::push_heap with greater): earliest expiry first, ties by slot, so retirement
  // order is deterministic. Plain vectors so that reserve() really reserves.
  std::vector<Expiry> expiries_;
  // Min-heap of dead slots: lowest first, deterministic recycling that keeps the live range
  // compact.
  std::vector<std::uint32_t> free_;
};

}  // namespace zonesim::gpu
