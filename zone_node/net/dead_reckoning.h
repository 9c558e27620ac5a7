#pragma once
// Sender-side first-order dead reckoning: the zone runs the receivers' model (position +
// velocity * elapsed) and sends an update only when the prediction is off by more than the
// threshold or the heartbeat has expired.

#include "common/entity_id.h"
#include "common/math.h"
#include "common/scene.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// What a receiver extrapolates at time t from the last state it was sent.
inline Vec3 predictFirstOrder(const DeadReckoningState& s, double t) {
  return s.pos + s.vel * (t - s.time);
}

/// This entity's heartbeat period: between 75% and 100% of the setting, fixed per id. Entities
/// first sent together (a keyframe, a scene start) would otherwise all beat in the same tick.
inline double heartbeatPeriod(EntityId id, const DeadReckoning& cfg) {
  double u = double(mix64(id.value) >> 11) * 0x1.0p-53;
  return cfg.heartbeat_seconds * (0.75 + 0.25 * u);
}

/// True when the receivers' prediction has drifted past the threshold or is too old.
inline bool needsUpdate(const DeadReckoningState& s, EntityId id, const Vec3& pos, double t,
                        const DeadReckoning& cfg) {
  if (t - s.time >= heartbeatPeriod(id, cfg)) return true;
  return (predictFirstOrder(s, t) - pos).squaredNorm() >
         cfg.position_threshold * cfg.position_threshold;
}

/// Records that (pos, vel) was sent at time t.
inline void markSent(DeadReckoningState& s, const Vec3& pos, const Vec3& vel, double t) {
  s.pos = pos;
  s.vel = vel;
  s.time = t;
}

}  // namespace zonesim::zone
