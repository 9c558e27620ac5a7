#pragma once
// The player protocol of a zone: avatars spawned and despawned at the gateways' request, inputs
// applied in sequence order exactly once (held across a gap, forwarded to the new owner after a
// handoff), owners announced to the gateways, and the time of each handoff from the border
// crossing to the first input applied. The tick calls it in its input and migrate phases;
// avatars move in a phase of their own (avatar_movement.h).

#include <cstdint>
#include <map>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "common/entity_id.h"
#include "zone_node/cluster/entity_codec.h"
#include "zone_node/departure.h"
#include "zone_node/entity_store.h"

namespace zonesim {
struct Scene;
}

namespace zonesim::zone {

class GatewayLink;
struct MigrationResult;
struct SpawnRequestMsg;
struct DespawnRequestMsg;
struct TickCounters;

/// A handoff that completed: the avatar's player, and the ticks from its arrival at this zone
/// (the tick it crossed the border) to the first input applied here.
struct CompletedHandoff {
  std::uint64_t player_id;
  std::uint64_t ticks;
};

/// What the protocol changes in its zone during a tick.
struct PlayerZone {
  EntityStore& store;
  IdSetDigest& ledger;              ///< created here minus destroyed here
  EntityIdAllocator& ids;           ///< ids of new avatars
  std::vector<Departure>& leavers;  ///< avatars destroyed here (the publisher says so)
  TickCounters& counters;
  GatewayLink* link;  ///< the gateways (null: no DDS)
  std::uint64_t tick;
};

/// The players of one zone.
class Players {
 public:
  /// `rank` of `ranks` zones: a new avatar is created by rank player_id % ranks. An avatar that
  /// gets no input for orphan_grace_ticks (its player left with a crashed gateway) is removed;
  /// 0: never.
  Players(const Scene& scene, int rank, int ranks, int orphan_grace_ticks = 0);

  /// The avatars a restart brought back to this zone: remembered as spawned, and their owner
  /// announced, since the gateways must learn where they live now. For kRestoreHoldTicks a gap
  /// in an avatar's inputs waits for the gateway to resend what the restart lost, and the
  /// announcement is repeated until it does: one written before a gateway's reader matched
  /// this new process never reaches that gateway (the topic is volatile).
  void restored(PlayerZone& zone);
  /// Input phase: the inputs forwarded with the last migration, then the gateways' spawn,
  /// despawn and input messages, then held inputs whose turn has come.
  void input(PlayerZone& zone);
  /// Migrate phase, after the exchange: handoffs out and in, avatars that arrived after their
  /// despawn, new avatars' first announcement; keeps the inputs other zones forwarded.
  void migrated(PlayerZone& zone, MigrationResult& result);

  /// Inputs for rank r's avatars, to pass on with the next migration (one queue per rank).
  std::vector<std::vector<ForwardedInput>>& forwardQueues() { return forward_; }
  /// Handoffs completed this tick: ticks from the avatar's arrival at this zone to the first
  /// input applied here.
  const std::vector<CompletedHandoff>& handoffsCompleted() const { return handoffs_completed_; }
  /// Forgets the last tick's handoff figures.
  void startTick() { handoffs_completed_.clear(); }

 private:
  void spawnAvatar(PlayerZone& zone, const SpawnRequestMsg& request);
  void applyInput(PlayerZone& zone, std::uint64_t player_id, std::uint32_t seq, float move_x,
                  float move_z);
  /// Applies held inputs whose turn has come, or whose gap has waited kInputHoldTicks.
  void releaseHeldInputs(PlayerZone& zone);
  void despawnAvatar(PlayerZone& zone, const DespawnRequestMsg& request);
  void destroyAt(PlayerZone& zone, std::size_t index);
  /// Removes the avatars that have gone orphan_grace_ticks without an input (checked once a
  /// second).
  void removeOrphans(PlayerZone& zone);
  /// Announces the restored avatars still waiting for their inputs to be resent.
  void announceAwaiting(PlayerZone& zone);

  const Scene& scene_;
  int rank_, ranks_;
  std::vector<EntityId> unannounced_;  // avatars created or received here, not yet announced
  std::vector<std::vector<ForwardedInput>> forward_;         // per destination rank
  std::vector<ForwardedInput> forwarded_in_;                 // to apply next input phase
  std::unordered_map<std::uint64_t, int> departed_players_;  // player -> rank its avatar went to
  std::unordered_set<std::uint64_t> known_players_;          // every spawn request seen
  std::unordered_set<std::uint64_t> despawned_players_;      // every despawn request obeyed
  // player -> the gateway session of its newest spawn request: a player that resumed at
  // another gateway leaves its old session behind, whose timeout must not remove the avatar.
  std::unordered_map<std::uint64_t, std::uint64_t> session_of_;
  struct HeldInput {
    float move_x, move_z;
    std::uint64_t since_tick;
  };
  static constexpr std::uint64_t kInputHoldTicks = 3;  // a forwarded input lags by one tick
  // After a restart the gateways resend each player's inputs since the restored one; they need
  // to see the new epoch and the avatar's announcement first (DDS discovery, a second or two).
  // Until the next input in sequence arrives, a restored avatar's gap waits this long.
  static constexpr std::uint64_t kRestoreHoldTicks = 150;
  static constexpr std::uint64_t kReannounceTicks = 10;
  std::uint64_t hold_until_tick_ = 0;                   // a restart's extended hold ends here
  std::unordered_set<std::uint64_t> awaiting_resend_;  // restored players, until in sequence
  std::uint64_t orphan_grace_ticks_;
  std::unordered_map<std::uint64_t, std::uint64_t> last_input_tick_;  // player -> tick heard
  std::map<std::uint64_t, std::map<std::uint32_t, HeldInput>> held_inputs_;  // player -> seq
  std::unordered_map<std::uint64_t, std::uint64_t> handoff_started_;  // player -> arrival tick
  std::vector<CompletedHandoff> handoffs_completed_;                  // completed this tick
};

}  // namespace zonesim::zone
