#pragma once
// A player's newest inputs, kept so that what a crash lost can be sent again. Both ends keep
// them: the gateway, for a zone restarted from a checkpoint, which announces each avatar with
// the last input it had applied then (the gateway resends everything after it); the client,
// for its gateway dying, since a resumed session's Welcome names the last input the zone
// applied. The zones apply each sequence number once, so a resend of what already arrived
// costs nothing but bytes.

#include <array>
#include <cstddef>
#include <cstdint>

namespace zonesim::gateway {

/// One input as it was sent.
struct InputRecord {
  std::uint32_t seq = 0;
  float move_x = 0, move_z = 0;
};

class InputHistory {
 public:
  /// 12.8 s of inputs at 20 a second: a checkpoint interval plus a restart.
  static constexpr std::size_t kCapacity = 256;

  /// Records an input; seqs must rise.
  void record(const InputRecord& in) {
    ring_[next_ % kCapacity] = in;
    ++next_;
  }
  /// Visits the kept inputs with seq >= from, oldest first; returns how many of the seqs
  /// from..newest it no longer holds (overwritten before they could be resent).
  template <typename F>
  std::uint32_t since(std::uint32_t from, F&& f) const {
    std::size_t kept = next_ < kCapacity ? next_ : kCapacity;
    std::uint32_t missing = 0;
    bool first = true;
    for (std::size_t k = next_ - kept; k < next_; ++k) {
      const InputRecord& in = ring_[k % kCapacity];
      if (in.seq < from) continue;
      if (first && in.seq > from) missing = in.seq - from;
      first = false;
      f(in);
    }
    return missing;
  }
  /// The newest seq recorded (0: none).
  std::uint32_t newest() const { return next_ == 0 ? 0 : ring_[(next_ - 1) % kCapacity].seq; }

 private:
  std::array<InputRecord, kCapacity> ring_{};
  std::size_t next_ = 0;
};

}  // namespace zonesim::gateway
