#pragma once
// A per-client downlink budget (Fiedler's priority accumulator, BigWorld's per-client priority
// queue): each gateway tick a client may be sent bytes_per_tick; guaranteed traffic (despawns,
// its own avatar, Welcome, Handoff, Pong, clock ticks) goes out regardless and is charged as
// debt. Spawns and updates share what is left, highest accumulated priority first; priority
// is the error as an angle seen by the viewer, so a near entity outranks a far one with the
// same error, and a spawn counts as an entity missing by kMissingEntityM. An update is only
// worth sending when the error the client sees exceeds max(zone threshold, angle * distance),
// so near entities stay at the zone's precision and far ones go coarse. Bytes are UDP payload.

#include <algorithm>
#include <cstdint>
#include <string>
#include "common/flat_id_map.h"
#include "gateway/world_cache.h"

namespace zonesim::gateway {

/// The budget's settings; kbps 0 = no budget (every update goes out as the zones sent it).
struct BudgetSettings {
  double kbps = 0;                  ///< kbit/s of UDP payload per client
  double error_angle_rad = 0.0087;  ///< error held as this angle seen from the viewer (0.5 deg)
  bool enabled() const { return kbps > 0; }
  /// Ticks over which a client's spawns and updates are gathered into one send: enough for
  /// about kGatherBytes, at most a third of a second. Chosen when a datagram's framing was
  /// 80 bytes, so that at a low rate a datagram a tick would not be mostly framing. With the
  /// lean frames' 13 (wire/downlink_frame.h), 150 B took the demo's 0-25 m band from p99
  /// 0.333 m to 0.24-0.26 m (docs/benchmarks.md), but the view's pressure (adaptRadius) is
  /// judged per send: a smaller send overflows more often though the rate suffices (a view
  /// spawning in), the view narrows, and the budget test's far NPCs were never spawned.
  /// Pacing the narrowing per second alone did not fix that (tried): smaller sends wait for
  /// pressure judged against the rate.
  int ticksPerSend(double tick_rate) const;
  /// Bytes each client may be sent per gateway tick: a second's bytes over tick_rate +
  /// ticksPerSend ticks, since a 1 s window that starts with one send can hold that many
  /// ticks' bytes.
  double bytesPerTick(double tick_rate) const {
    return kbps * 1000.0 / 8.0 / (tick_rate + ticksPerSend(tick_rate));
  }
  /// What a client's spawns and updates are gathered to, bytes.
  static constexpr double kGatherBytes = 400;
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

/// What not showing an entity at all counts as when ranked against errors: about a body's size.
inline constexpr double kMissingEntityM = 1.0;
/// Nearer than this, priority stops growing (an entity on top of the viewer).
inline constexpr double kNearestM = 1.0;

/// Priority a tick adds for an error of error_m at distance_m from the viewer: the error as an
/// angle, radians.
inline double errorPriority(double error_m, double distance_m) {
  return error_m / std::max(distance_m, kNearestM);
}

/// One client's budget: tokens, per entity the state last sent and its accumulator, and the
/// accumulators of spawns still waiting.
class DownlinkBudget {
 public:
  /// Adds the bytes of the time since the last refill, holding at most cap_bytes (a send's
  /// worth, or one spawn datagram where that is more): any window of t seconds then carries at
  /// most t seconds' bytes plus the cap plus the guaranteed traffic's overdraft.
  void refill(double bytes, double cap_bytes);
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
  /// The radius the client is shown under this budget (+inf until first pressed).
  double viewRadius() const { return view_radius_; }
  /// After a send: shrinks the view radius by kShrink when something ranked did not fit
  /// (pressed), else grows it by kGrow, within [least, nimbus]. Fewer entities shown is the
  /// price of keeping the shown ones current: a far entity never updated drifts by metres.
  void adaptRadius(bool pressed, double nimbus, double least);
  static constexpr double kShrink = 0.97, kGrow = 1.003;
  /// A spawn waiting its turn: its accumulated priority after adding priority this tick.
  double accumulateSpawn(std::uint64_t id, double priority);
  /// Ends a tick: a waiting spawn not accumulated in it (sent, or out of view) stops waiting.
  void endTick();
  std::size_t waitingSpawns() const { return waiting_.size(); }

 private:
  struct Tracked {
    CachedEntity sent;
    bool has_sent = false;
    double accumulator = 0;
  };
  double tokens_ = 0;
  double view_radius_ = 1e30;
  // Flat maps: these are looked up for every entity in every player's view each tick.
  FlatIdMap<Tracked> entities_;
  // Accumulators of spawns: last tick's, and this tick's (swapped at endTick, so nothing that
  // left the view stays; clear() keeps the slots, so no allocation in a steady state).
  FlatIdMap<double> waiting_, waiting_next_;
};

}  // namespace zonesim::gateway
