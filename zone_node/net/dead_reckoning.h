#pragma once
// Sender-side first-order dead reckoning: the zone runs the receivers' model (position +
// velocity * elapsed) and sends an update only when the prediction is off by more than the
// threshold or the heartbeat has expired.

#include "common/math.h"
#include "common/scene.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

/// What a receiver extrapolates at time t from the last state it was sent.
inline Vec3 predictFirstOrder(const DeadReckoningState& s, double t) {
  return s.pos + s.vel * (t - s.time);
}

/// True when the receivers' prediction has drifted past the threshold or is too old.
inline bool needsUpdate(const DeadReckoningState& s, const Vec3& pos, double t,
                        const DeadReckoning& cfg) {
  if (t - s.time >= cfg.heartbeat_seconds) return true;
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
