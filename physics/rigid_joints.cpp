#include "physics/rigid_joints.h"

#include "physics/solver_row.h"

namespace zonesim::physics {

std::uint32_t RigidJoints::addBall(const BallJoint& joint) {
  balls_.push_back(joint);
  return static_cast<std::uint32_t>(balls_.size() - 1);
}

std::uint32_t RigidJoints::addHinge(const HingeJoint& joint) {
  HingeJoint h = joint;
  h.axis_a.normalize();
  h.axis_b.normalize();
  hinges_.push_back(h);
  return static_cast<std::uint32_t>(hinges_.size() - 1);
}

void RigidJoints::markBodies(std::span<std::uint8_t> touched) const {
  auto mark = [&](BodyIndex a, BodyIndex b) {
    touched[a] = 1;
    if (b != kNoBody) touched[b] = 1;
  };
  for (const BallJoint& j : balls_) mark(j.a, j.b);
  for (const HingeJoint& j : hinges_) mark(j.a, j.b);
}

void RigidJoints::addPointRows(const BodyStorage& bodies, const Anchor& anchor, double rate,
                               std::size_t& next) {
  const bool fixed = anchor.b == kNoBody;
  const Vec3 ra = bodies.orientation[anchor.a] * anchor.local_a;
  const Vec3 rb = fixed ? Vec3::Zero() : Vec3(bodies.orientation[anchor.b] * anchor.local_b);
  const Vec3 pa = bodies.position[anchor.a] + ra;
  const Vec3 pb = fixed ? anchor.local_b : Vec3(bodies.position[anchor.b] + rb);
  // Rows along the lever arm and across it rather than along the world axes: for a round body
  // these are the effective mass's eigenvectors, so the rows do not fight each other (along
  // world axes a 2 m pendulum at dt 1/60 and 10 iterations kept a 2 cm gap).
  const Vec3 arm = ra.squaredNorm() > 1e-18 ? ra : rb;
  const Vec3 u = arm.squaredNorm() > 1e-18 ? Vec3(arm.normalized()) : Vec3::UnitX();
  const Vec3 v = solver_row::orthogonal(u);
  const Vec3 basis[3] = {u, v, u.cross(v)};
  for (int axis = 0; axis < 3; ++axis) {
    Row& r = rows_[next++];
    r.a = anchor.a;
    r.b = anchor.b;
    setLinearRow(r, bodies, r.a, r.b, ra, rb, basis[axis]);
    r.bias = rate * (pb - pa).dot(r.d);
  }
}

void RigidJoints::addAngularRow(const BodyStorage& bodies, BodyIndex a, BodyIndex b, const Vec3& u,
                                double error, double rate, std::size_t& next) {
  const bool fixed = b == kNoBody;
  Row& r = rows_[next++];
  r.a = a;
  r.b = b;
  r.d = Vec3::Zero();
  r.ca = u;
  r.cb = u;
  r.wa = bodies.inv_inertia_world[a] * u;
  r.wb = fixed ? Vec3::Zero() : Vec3(bodies.inv_inertia_world[b] * u);
  r.ma = r.mb = 0.0;
  const double inv = u.dot(r.wa) + (fixed ? 0.0 : u.dot(r.wb));
  r.mass = inv > 0.0 ? 1.0 / inv : 0.0;
  r.bias = rate * error;
}

std::pair<std::size_t, std::size_t> RigidJoints::rowsOf(std::size_t i) const {
  if (i < balls_.size()) return {3 * i, 3};
  return {3 * balls_.size() + 5 * (i - balls_.size()), 5};
}

std::array<double, RigidJoints::kWarmValues> RigidJoints::warmState(std::size_t i) const {
  std::array<double, kWarmValues> out{};
  const auto [first, count] = rowsOf(i);
  for (std::size_t r = 0; r < count && first + r < rows_.size(); ++r)
    out[r] = rows_[first + r].impulse;
  if (i < soft_.size()) {
    for (int k = 0; k < 3; ++k) {
      out[5 + k] = soft_[i].linear[k];
      out[8 + k] = soft_[i].angular[k];
    }
  }
  return out;
}

void RigidJoints::setWarmState(std::size_t i, const std::array<double, kWarmValues>& values) {
  // The rows and soft joints of a new world are made here, as prepare would make them; each
  // keeps the impulse it is given until prepare reads it.
  rows_.resize(3 * balls_.size() + 5 * hinges_.size());
  const auto [first, count] = rowsOf(i);
  for (std::size_t r = 0; r < count; ++r) rows_[first + r].impulse = values[r];
  soft_.resize(balls_.size() + hinges_.size());
  for (int k = 0; k < 3; ++k) {
    soft_[i].linear[k] = values[5 + k];
    soft_[i].angular[k] = values[8 + k];
  }
}

void RigidJoints::prepare(const BodyStorage& bodies, double dt, double beta) {
  // Last step's impulses, in row order (the joint list only grows, at the end).
  stored_.resize(rows_.size());
  for (std::size_t i = 0; i < rows_.size(); ++i) stored_[i] = rows_[i].impulse;
  rows_.resize(3 * balls_.size() + 5 * hinges_.size());
  const double rate = beta / dt;
  std::size_t next = 0;
  for (const BallJoint& j : balls_) {
    addPointRows(bodies, Anchor{j.a, j.b, j.local_a, j.local_b}, rate, next);
  }
  for (const HingeJoint& j : hinges_) {
    addPointRows(bodies, Anchor{j.a, j.b, j.local_a, j.local_b}, rate, next);
    const Vec3 axis_a = bodies.orientation[j.a] * j.axis_a;
    const Vec3 axis_b = j.b == kNoBody ? j.axis_b : Vec3(bodies.orientation[j.b] * j.axis_b);
    // Two directions perpendicular to A's axis, by a fixed rule (deterministic basis).
    const Vec3 p = solver_row::orthogonal(axis_a);
    const Vec3 q = axis_a.cross(p);
    // B is turned from A's axis by about a_A x a_B (small angles): its parts along p and q
    // are the errors; the rows stop relative rotation about p and q.
    const Vec3 tilt = axis_a.cross(axis_b);
    addAngularRow(bodies, j.a, j.b, p, p.dot(tilt), rate, next);
    addAngularRow(bodies, j.a, j.b, q, q.dot(tilt), rate, next);
  }
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    rows_[i].impulse = i < stored_.size() ? stored_[i] : 0.0;
  }
}

void RigidJoints::warmStart(BodyStorage& bodies) {
  for (const Row& r : rows_) applyRow(r, bodies, r.a, r.b, r.impulse);
}

void RigidJoints::iterate(BodyStorage& bodies) {
  for (Row& r : rows_) {
    const double cdot = rowVelocity(r, bodies, r.a, r.b);
    const double lambda = -r.mass * (cdot + r.bias);
    r.impulse += lambda;
    applyRow(r, bodies, r.a, r.b, lambda);
  }
}

}  // namespace zonesim::physics
