#pragma once
// A per-client downlink budget (Fiedler's priority accumulator, BigWorld's per-client priority
// queue): each gateway tick a client may be sent bytes_per_tick; guaranteed traffic (despawns,
// its own avatar, Welcome, Handoff, Pong, clock ticks) goes out regardless and is charged as
// debt; spawns (nearest first) and then updates (highest accumulated priority first) take what
// is left. An update is only worth sending when the error the client sees exceeds an angle at
// the viewer: max(zone threshold, angle * distance), so near entities stay at the zone's
// precision and far ones go coarse. Bytes are UDP payload bytes.

#include <cstdint>
#include <string>
#include <unordered_map>

#include "gateway/world_cache.h"

namespace zonesim::gateway {

/// The budget's settings; kbps 0 = no budget (every update goes out as the zones sent it).
struct BudgetSettings {
  double kbps = 0;                  ///< kbit/s of UDP payload per client
  double error_angle_rad = 0.0087;  ///< error held as this angle seen from the viewer (0.5 deg)
  bool enabled() const { return kbps > 0; }
  /// Bytes each client may be sent per gateway tick: a second's bytes over tick_rate + 1 ticks,
  /// since a 1 s window that starts with one tick's datagrams can hold tick_rate + 1 ticks'.
  double bytesPerTick(double tick_rate) const { return kbps * 1000.0 / 8.0 / (tick_rate + 1); }
};

/// Throws std::invalid_argument naming `kbps_name` / `angle_name` when a setting is negative,
/// not finite, or too small for one second to carry a datagram of min_datagram_bytes (a spawn).
void checkBudget(const BudgetSettings& b, std::size_t min_datagram_bytes,
                 const std::string& kbps_name, const std::string& angle_name);

/// The error (metres, and radians) a client sees for an entity: where it extrapolates the state
/// it was sent, against where the newest state puts the entity, both at sim time `at`.
struct ShownError {
  double position = 0, orientation = 0;
};
ShownError shownError(const CachedEntity& sent, const CachedEntity& newest, double at);

/// One client's budget: tokens, and per entity the state last sent and its accumulator.
class DownlinkBudget {
 public:
  /// Adds one tick's bytes, holding at most cap_bytes (one tick's worth, or one spawn datagram
  /// where that is more): any window of n ticks then carries at most n ticks' bytes plus the cap
  /// plus the guaranteed traffic's overdraft.
  void refill(double bytes_per_tick, double cap_bytes);
  double tokens() const { return tokens_; }
  /// Charges bytes sent (may go negative: guaranteed traffic is never held back).
  void spend(std::size_t bytes) { tokens_ -= double(bytes); }

  /// The state the client was last sent for id, or nullptr.
  const CachedEntity* lastSent(std::uint64_t id) const;
  /// The entity's accumulated priority after adding priority this tick.
  double accumulate(std::uint64_t id, double priority);
  /// The client was sent this state: it becomes the reference, the accumulator restarts.
  void sent(std::uint64_t id, const CachedEntity& e);
  /// The client no longer holds the entity.
  void forget(std::uint64_t id) { entities_.erase(id); }

 private:
  struct Tracked {
    CachedEntity sent;
    bool has_sent = false;
    double accumulator = 0;
  };
  double tokens_ = 0;
  std::unordered_map<std::uint64_t, Tracked> entities_;
};

}  // namespace zonesim::gateway
