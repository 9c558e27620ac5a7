#pragma once
// The gateway's one timeline across cluster epochs. A zone cluster restarted from a checkpoint
// (a new epoch, idl/zonesim.idl) ticks again from the checkpoint's tick, earlier than what the
// gateway has already told its clients. Rather than rewinding every client's clock, the gateway
// maps each epoch's ticks and sim times onto its own, continuing just after the newest it
// mapped: the restored world then reads as newer than anything cached, wins every comparison
// of age (cache, tombstones, ownership, clients' clocks), and players see their entities jump
// back to where the checkpoint had them, not a disconnect. Samples of an older epoch than the
// newest seen are dropped: they come from zones that are no longer the world.
//
// Epoch 0 maps onto itself, so a cluster that never restarts sees no change at all; so does the
// first epoch a gateway sees, whichever it is (a gateway started after a restart).

#include <cstdint>
#include <optional>

namespace zonesim::gateway {

/// A sample's tick and sim time on the gateway's timeline.
struct MappedTime {
  std::uint64_t tick = 0;
  double sim_time = 0;
};

class EpochTimeline {
 public:
  /// dt: sim seconds per zone tick (the gap left between the epochs' timelines).
  explicit EpochTimeline(double dt) : dt_(dt) {}

  /// The sample's tick on the gateway's timeline; nullopt (counted) for an old epoch. A newer
  /// epoch is entered here: its ticks continue after the newest mapped so far.
  std::optional<std::uint64_t> mapTick(std::uint32_t epoch, std::uint64_t tick);
  /// The same for a sample with a sim time as well.
  std::optional<MappedTime> map(std::uint32_t epoch, std::uint64_t tick, double sim_time);

  std::uint32_t epoch() const { return epoch_; }
  /// Epochs entered since the start (0 for a cluster that never restarted).
  std::uint32_t epochsEntered() const { return entered_; }
  /// Samples dropped for an old epoch.
  std::uint64_t stale() const { return stale_; }

 private:
  /// False (counted) for an old epoch; enters a newer one.
  bool admit(std::uint32_t epoch);

  double dt_;
  std::uint32_t epoch_ = 0;
  std::uint32_t entered_ = 0;
  std::uint64_t stale_ = 0;
  // Offsets of the current epoch, set by its first sample with a tick, and with a sim time.
  std::optional<std::int64_t> tick_offset_ = 0;
  std::optional<double> sim_offset_ = 0.0;
  std::uint64_t newest_tick_ = 0;  // newest mapped, of any epoch
  double newest_sim_ = 0;
  bool mapped_any_ = false, mapped_sim_ = false;  // a tick, a sim time mapped yet
};

}  // namespace zonesim::gateway
