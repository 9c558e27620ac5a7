#include "zone_node/net/dead_reckoning.h"

#include <algorithm>
#include <array>
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
    case EntityKind::Item:  // lies where it is until taken
      return {dr::Order::Static, dr::Spin::Fixed};
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

MotionEstimate estimateMotion(const DeadReckoningState& d, const Vec3& vel, double dt) {
  MotionEstimate e{vel, Vec3::Zero(), MotionEstimate::Kind::None};
  if (!d.has_last || dt <= 0 || d.vel_count == 0) return e;
  // The window oldest first, the current velocity last.
  constexpr int kWindow = DeadReckoningState::kVelocityWindow;
  std::array<Vec3, kWindow + 1> v;
  int n = d.vel_count;
  int first = n < kWindow ? 0 : d.vel_next;
  for (int k = 0; k < n; ++k) v[k] = d.vel_history[(first + k) % kWindow];
  v[n] = vel;
  Vec3 mean_acc = (v[n] - v[0]) / (n * dt);
  double spread = 0, variation = 0;
  for (int k = 0; k < n; ++k) {
    Vec3 step = v[k + 1] - v[k];
    spread = std::max(spread, (step / dt - mean_acc).norm());
    variation += step.norm();
  }
  if (spread <= std::max(kSteadyAccelerationTolerance, 0.25 * mean_acc.norm())) {
    e.acc = mean_acc;  // free flight, steady braking: the window agrees
    e.kind = MotionEstimate::Kind::Steady;
  } else if ((v[n] - v[0]).norm() < 0.5 * variation) {
    // The velocity goes back and forth (a body jittering in resting or rolling contact): its
    // mean over the window predicts better than any one tick, and no acceleration does. The
    // last n velocities: their mean is the displacement over n ticks (p += v dt).
    Vec3 sum = Vec3::Zero();
    for (int k = 1; k <= n; ++k) sum += v[k];
    e.vel = sum / n;
    e.kind = MotionEstimate::Kind::Oscillating;
  } else {
    e.kind = MotionEstimate::Kind::Changing;  // an impact or a turn: first order until it settles
  }
  return e;
}

dr::State trueState(const EntityStore& store, std::size_t i, double dt) {
  dr::State s;
  s.pos = toDr(store.pos[i]);
  const Quat& q = store.rot[i];
  s.rot = {q.x(), q.y(), q.z(), q.w()};
  const DeadReckoningState& d = store.dr[i];
  bool history = d.has_last && dt > 0;
  bool rigid = store.kind[i] == EntityKind::RigidBody;
  if (rigid && store.body[i].sleeping) {
    s.vel = {};  // asleep: it does not move until something wakes it (static state)
    return s;
  }
  MotionEstimate m = estimateMotion(d, store.vel[i], dt);
  s.vel = toDr(m.vel);
  s.acc = toDr(m.acc);
  if (rigid) {
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
  constexpr int kWindow = DeadReckoningState::kVelocityWindow;
  d.vel_history[d.vel_next] = store.vel[i];
  d.vel_next = (d.vel_next + 1) % kWindow;
  d.vel_count = std::min(d.vel_count + 1, kWindow);
  d.last_rot = store.rot[i];
  d.has_last = true;
}

namespace {
bool moving(const dr::State& s) {
  auto nonzero = [](const dr::V3& v) { return v.x != 0 || v.y != 0 || v.z != 0; };
  return nonzero(s.vel) || nonzero(s.acc) || nonzero(s.angvel);
}
}  // namespace

dr::Due DeadReckoner::due(const DeadReckoningState& sent, EntityId id, EntityKind kind,
                          const dr::State& truth, double now) const {
  // A body that fell asleep is told at once, so receivers stop extrapolating its last motion.
  if (!moving(truth) && moving(sent.sent)) return dr::Due::Rest;
  return dr::updateDue(sent.sent, modelFor(cfg_, kind), now - sent.time, truth.pos, truth.rot,
                       thresholds_, dr::heartbeatPeriod(id.value, cfg_.heartbeat_seconds));
}

}  // namespace zonesim::zone
