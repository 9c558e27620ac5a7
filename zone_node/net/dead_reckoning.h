#pragma once
// Sender-side dead reckoning: the zone runs the receivers' model (dr/dr_model.h, the order and
// orientation mode chosen per entity type in the scene) on the quantised state it last sent, and
// sends an update only when the prediction is off by more than the position or orientation
// threshold or the entity's heartbeat has expired.

#include "common/math.h"
#include "common/scene_dead_reckoning.h"
#include "dr/dr_model.h"
#include "dr/state_codec.h"
#include "zone_node/entity_store.h"
#include "zone_node/net/dead_reckoning_state.h"

namespace zonesim::zone {

/// The scene's model for an entity kind.
dr::Model modelFor(const DeadReckoning& cfg, EntityKind kind);
/// The scene's thresholds in the model's units.
dr::Thresholds thresholdsOf(const DeadReckoning& cfg);

/// Per-tick acceleration estimates within this of their window mean (m/s^2) count as steady.
constexpr double kSteadyAccelerationTolerance = 2.0;

/// What the sender tells receivers of an entity's motion, from its velocity over the window.
struct MotionEstimate {
  /// Steady: the per-tick accelerations agree (free flight, braking), acc is their mean.
  /// Oscillating: the velocity jitters about a mean (contact): vel is that mean, acc zero.
  /// Changing: an impact or turn: the velocity now, acc zero. None: no history yet.
  enum class Kind : std::uint8_t { None, Steady, Oscillating, Changing };
  Vec3 vel, acc;
  Kind kind;
};

/// The motion to send for an entity whose velocity is `vel` now, given the last ticks' in d
/// (dt apart). Contact solvers make a resting or rolling body's velocity flip tick to tick;
/// one tick's difference would give second-order receivers an acceleration of tens of m/s^2.
MotionEstimate estimateMotion(const DeadReckoningState& d, const Vec3& vel, double dt);

/// The entity's true state now, with the motion of estimateMotion (a sleeping rigid body: at
/// rest). Angular velocity is the solver's for rigid bodies, otherwise estimated from the
/// previous tick's orientation; dt <= 0 means no previous tick, and the estimates are zero.
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
