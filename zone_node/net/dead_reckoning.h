#pragma once
// Sender-side dead reckoning: the zone runs the receivers' model (idl/dr_model.h, the order and
// orientation mode chosen per entity type in the scene) on the quantised state it last sent, and
// sends an update only when the prediction is off by more than the position or orientation
// threshold or the entity's heartbeat has expired.

#include "common/math.h"
#include "common/scene.h"
#include "idl/dr_model.h"
#include "idl/state_codec.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// The scene's model for an entity kind.
dr::Model modelFor(const DeadReckoning& cfg, EntityKind kind);
/// The scene's thresholds in the model's units.
dr::Thresholds thresholdsOf(const DeadReckoning& cfg);

/// The entity's true state now. Acceleration (and, except for rigid bodies, whose solver knows
/// it, angular velocity) is estimated from the previous tick's velocity and orientation kept in
/// store.dr[i]; dt <= 0 means no previous tick, and the estimates are zero.
dr::State trueState(const EntityStore& store, std::size_t i, double dt);
/// Keeps this tick's velocity and orientation for the next tick's estimates.
void rememberTick(EntityStore& store, std::size_t i);

/// Decides and records what receivers are told about one entity.
class DeadReckoner {
 public:
  DeadReckoner(const DeadReckoning& cfg, const dr::CodecParams& codec)
      : cfg_(cfg), thresholds_(thresholdsOf(cfg)), codec_(codec) {}

  /// Why an update is due now (None if receivers' prediction is still good).
  dr::Due due(const DeadReckoningState& sent, EntityId id, EntityKind kind, const dr::State& truth,
              double now) const;
  /// The state receivers will decode for truth sent relative to `cell` now; *largest gets
  /// the smallest-three index used (carried along so re-encoding picks the same).
  dr::State quantised(const dr::State& truth, EntityKind kind, int cell, int* largest) const {
    return codec_.roundTrip(truth, modelFor(cfg_, kind), cell, largest);
  }
  /// Records that `sent` (already quantised) went out at time now.
  static void markSent(DeadReckoningState& s, const dr::State& sent, double now) {
    s.sent = sent;
    s.time = now;
  }
  const dr::StateCodec& codec() const { return codec_; }
  const DeadReckoning& config() const { return cfg_; }

 private:
  DeadReckoning cfg_;
  dr::Thresholds thresholds_;
  dr::StateCodec codec_;
};

}  // namespace zonesim::zone
