#pragma once
// A per-client downlink budget (Fiedler's priority accumulator, BigWorld's per-client priority
// queue): each gateway tick a client may be sent bytes_per_tick; guaranteed traffic (the
// avatar, Welcome, Handoff, Pong, clock ticks) goes out regardless and is charged as
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
  /// What a client's spawns and updates are gathered to before they go, bytes (see
  /// ticksPerSend). Small sends show states sooner; each datagram costs its framing (13 B
  /// in lean frames, wire/downlink_frame.h) plus 28 B of UDP/IP that the budget does not count.
  double send_bytes = kDefaultSendBytes;
  static constexpr double kDefaultSendBytes = 150;
  bool enabled() const { return kbps > 0; }
  /// Ticks over which a client's spawns and updates are gathered into one send: enough for
  /// about send_bytes, at most a third of a second. 150 B is 2 ticks at 20 kbit/s and 30 Hz.
  int ticksPerSend(double tick_rate) const;
  /// Bytes each client may be sent per gateway tick: a second's bytes over tick_rate +
  /// ticksPerSend + 1 ticks, since a 1 s window that starts with a full bucket (a send and
  /// the tick's bytes it may wait for) can hold that many ticks' bytes.
  double bytesPerTick(double tick_rate) const {
    return kbps * 1000.0 / 8.0 / (tick_rate + ticksPerSend(tick_rate) + 1);
  }
  /// The budget in bytes per second.
  double bytesPerSecond() const { return kbps * 1000.0 / 8.0; }
};

/// Throws std::invalid_argument naming `kbps_name` / `angle_name` when a setting is negative,
/// not finite, or too small for one second to carry a datagram of min_datagram_bytes (a spawn),
/// and naming --budget-send-bytes when send_bytes is not a positive number of bytes.
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
  /// worth, or one spawn datagram where that is more, and a tick's bytes): any window of t
  /// seconds then carries at most t seconds' bytes plus the cap plus the guaranteed traffic's
  /// overdraft.
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
  /// After a send that took `taken` of the ranked records in `available` bytes and left
  /// `waiting`, `waiting_near` of them updates of the near band: whether that presses the view.
  /// It does when a near update has to wait (the near band is to stay at the zone's
  /// precision), or when what waits would take more than kBacklogSeconds of the budget
  /// (bytes_per_second) to send. Judged against the rate, not per send, so that a small send
  /// leaving far records or a view's spawns to the next is no pressure unless the backlog is
  /// long. A record's bytes are this send's (available over taken) or, when none went, the
  /// last send's.
  bool pressed(std::size_t taken, std::size_t waiting, std::size_t waiting_near, double available,
               double bytes_per_second);
  static constexpr double kBacklogSeconds = 0.5;
  /// Narrows the view radius while pressed, else widens it, at kShrinkPerSecond and
  /// kGrowPerSecond over `seconds` since the last call, within [least, nimbus]. Fewer entities
  /// shown is the price of keeping the shown ones current: a far entity never updated drifts
  /// by metres.
  void adaptRadius(bool pressed, double nimbus, double least, double seconds);
  static constexpr double kShrinkPerSecond = 0.833, kGrowPerSecond = 1.018;
  /// Seconds since the last call (0 at the first, at most 1), for adaptRadius: sends come as
  /// often as the bucket fills, so the view changes at its rate per second, not per send.
  double secondsSinceAdapt(std::int64_t now_ns);
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
  double record_bytes_ = 0;  // what a ranked record took in the last send that carried one
  std::int64_t last_adapt_ns_ = -1;
  // Flat maps: these are looked up for every entity in every player's view each tick.
  FlatIdMap<Tracked> entities_;
  // Accumulators of spawns: last tick's, and this tick's (swapped at endTick, so nothing that
  // left the view stays; clear() keeps the slots, so no allocation in a steady state).
  FlatIdMap<double> waiting_, waiting_next_;
};

}  // namespace zonesim::gateway
