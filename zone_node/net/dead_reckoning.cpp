#include "zone_node/net/dead_reckoning.h"

#include <cmath>

namespace zonesim::zone {

namespace {
constexpr double kDegree = 3.14159265358979323846 / 180;

dr::V3 toDr(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}
}  // namespace

dr::Model modelFor(const DeadReckoning& cfg, EntityKind kind) {
  const DeadReckoningModel* m = &cfg.npc;
  switch (kind) {
    case EntityKind::Npc:
      m = &cfg.npc;
      break;
    case EntityKind::Avatar:
      m = &cfg.avatar;
      break;
    case EntityKind::RigidBody:
      m = &cfg.rigid_body;
      break;
    case EntityKind::Emitter:
      m = &cfg.emitter;
      break;
  }
  return {dr::Order(int(m->order)), m->rotating ? dr::Spin::Rotating : dr::Spin::Fixed};
}

dr::Thresholds thresholdsOf(const DeadReckoning& cfg) {
  return {cfg.position_threshold, cfg.orientation_threshold_deg * kDegree, cfg.heartbeat_seconds};
}

dr::State trueState(const EntityStore& store, std::size_t i, double dt) {
  dr::State s;
  s.pos = toDr(store.pos[i]);
  s.vel = toDr(store.vel[i]);
  const Quat& q = store.rot[i];
  s.rot = {q.x(), q.y(), q.z(), q.w()};
  const DeadReckoningState& d = store.dr[i];
  bool history = d.has_last && dt > 0;
  if (history) s.acc = toDr((store.vel[i] - d.last_vel) / dt);
  if (store.kind[i] == EntityKind::RigidBody) {
    s.angvel = toDr(store.body[i].angular_velocity);
  } else if (history) {
    // World-frame rate from the change this tick: q = dq * q_last, dq = exp(w dt / 2).
    Quat dq = (q * d.last_rot.conjugate()).normalized();
    if (dq.w() < 0) dq.coeffs() = -dq.coeffs();
    Vec3 axis = dq.vec();
    double s_half = axis.norm();
    if (s_half > 1e-12) s.angvel = toDr(axis * (2 * std::atan2(s_half, dq.w()) / (s_half * dt)));
  }
  return s;
}

void rememberTick(EntityStore& store, std::size_t i) {
  DeadReckoningState& d = store.dr[i];
  d.last_vel = store.vel[i];
  d.last_rot = store.rot[i];
  d.has_last = true;
}

dr::Due DeadReckoner::due(const DeadReckoningState& sent, EntityId id, EntityKind kind,
                          const dr::State& truth, double now) const {
  return dr::updateDue(sent.sent, modelFor(cfg_, kind), now - sent.time, truth.pos, truth.rot,
                       thresholds_, dr::heartbeatPeriod(id.value, cfg_.heartbeat_seconds));
}

}  // namespace zonesim::zone
