#include "dr/dr_model.h"

#include <algorithm>
#include <cmath>

#include "common/splitmix.h"

namespace zonesim::dr {

namespace {
Q4 multiply(const Q4& a, const Q4& b) {
  return {
      a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
      a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
}  // namespace

V3 predictPosition(const State& s, Order order, double dt) {
  switch (order) {
    case Order::Static:
      return s.pos;
    case Order::First:
      return {s.pos.x + s.vel.x * dt, s.pos.y + s.vel.y * dt, s.pos.z + s.vel.z * dt};
    case Order::Second: {
      double h = 0.5 * dt * dt;
      return {s.pos.x + s.vel.x * dt + s.acc.x * h, s.pos.y + s.vel.y * dt + s.acc.y * h,
              s.pos.z + s.vel.z * dt + s.acc.z * h};
    }
  }
  return s.pos;
}

V3 predictVelocity(const State& s, Order order, double dt) {
  switch (order) {
    case Order::Static:
      return {};
    case Order::First:
      return s.vel;
    case Order::Second:
      return {s.vel.x + s.acc.x * dt, s.vel.y + s.acc.y * dt, s.vel.z + s.acc.z * dt};
  }
  return {};
}

Q4 predictRotation(const State& s, Spin spin, double dt) {
  if (spin == Spin::Fixed) return s.rot;
  // Constant world-frame angular velocity w: q(t) = exp(w t / 2) * q0.
  double wx = s.angvel.x, wy = s.angvel.y, wz = s.angvel.z;
  double rate = std::sqrt(wx * wx + wy * wy + wz * wz);
  if (rate * dt == 0) return s.rot;
  double half = 0.5 * rate * dt, k = std::sin(half) / rate;
  Q4 step{wx * k, wy * k, wz * k, std::cos(half)};
  return normalized(multiply(step, s.rot));
}

double distance(const V3& a, const V3& b) {
  double dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double angleBetween(const Q4& a, const Q4& b) {
  // r = conj(a) * b; its angle is 2 atan2(|r.xyz|, |r.w|) (q and -q are one rotation). atan2
  // keeps full precision near zero, where acos of a dot product would not.
  Q4 r = multiply({-a.x, -a.y, -a.z, a.w}, b);
  double v = std::sqrt(r.x * r.x + r.y * r.y + r.z * r.z);
  return 2.0 * std::atan2(v, std::abs(r.w));
}

Q4 normalized(const Q4& q) {
  double n = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
  if (!(n > 1e-12) || !std::isfinite(n)) return {};
  return {q.x / n, q.y / n, q.z / n, q.w / n};
}

Due updateDue(const State& sent, const Model& m, double elapsed, const V3& true_pos,
              const Q4& true_rot, const Thresholds& t, double heartbeat_s) {
  if (elapsed >= heartbeat_s) return Due::Heartbeat;
  if (distance(predictPosition(sent, m.order, elapsed), true_pos) > t.position)
    return Due::Position;
  if (angleBetween(predictRotation(sent, m.spin, elapsed), true_rot) > t.orientation_rad)
    return Due::Orientation;
  return Due::None;
}

double heartbeatPeriod(std::uint64_t id, double heartbeat_s) {
  double u = double(splitmix64(id) >> 11) * 0x1.0p-53;
  return heartbeat_s * (0.75 + 0.25 * u);
}

}  // namespace zonesim::dr
