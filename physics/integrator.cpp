#include "physics/integrator.h"

namespace zonesim::physics {

int integratorOrder(Integrator kind) {
  switch (kind) {
    case Integrator::ExplicitEuler:
    case Integrator::SemiImplicitEuler:
      return 1;
    case Integrator::PositionVerlet:
    case Integrator::VelocityVerlet:
    case Integrator::Rk2Midpoint:
      return 2;
    case Integrator::Rk4:
      return 4;
  }
  return 0;
}

void LinearIntegrator::resize(std::size_t n) {
  // Grows only: after the first step of a given size nothing is allocated.
  for (auto* buffer : {&a1_, &a2_, &a3_, &a4_, &xs_, &vs_, &v2_, &v3_, &v4_}) {
    if (buffer->size() < n) buffer->resize(n);
  }
}

void LinearIntegrator::step(Integrator kind, const ForceModel& forces, const LinearStateView& state,
                            double dt) {
  resize(state.x.size());
  switch (kind) {
    case Integrator::ExplicitEuler:
      return explicitEuler(forces, state, dt);
    case Integrator::SemiImplicitEuler:
      return semiImplicitEuler(forces, state, dt);
    case Integrator::PositionVerlet:
      return positionVerlet(forces, state, dt);
    case Integrator::VelocityVerlet:
      return velocityVerlet(forces, state, dt);
    case Integrator::Rk2Midpoint:
      return rk2Midpoint(forces, state, dt);
    case Integrator::Rk4:
      return rk4(forces, state, dt);
  }
}

void LinearIntegrator::explicitEuler(const ForceModel& f, const LinearStateView& s, double dt) {
  const std::size_t n = s.x.size();
  std::span<Vec3> a(a1_.data(), n);
  evaluateAccelerations(f, s.x, s.v, s.inv_mass, s.external_force, a);
  for (std::size_t i = 0; i < n; ++i) {
    s.x_out[i] = s.x[i] + dt * s.v[i];
    s.v_out[i] = s.v[i] + dt * a[i];
  }
}

void LinearIntegrator::semiImplicitEuler(const ForceModel& f, const LinearStateView& s, double dt) {
  const std::size_t n = s.x.size();
  std::span<Vec3> a(a1_.data(), n);
  evaluateAccelerations(f, s.x, s.v, s.inv_mass, s.external_force, a);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 v = s.v[i] + dt * a[i];
    s.v_out[i] = v;
    s.x_out[i] = s.x[i] + dt * v;
  }
}

void LinearIntegrator::positionVerlet(const ForceModel& f, const LinearStateView& s, double dt) {
  // Stoermer: x+ = 2x - x- + a dt^2. The velocity is not part of the recurrence; it is
  // reconstructed to second order as (x+ - x)/dt + a(x+) dt/2 for drag and for the caller.
  const std::size_t n = s.x.size();
  std::span<Vec3> a(a1_.data(), n);
  evaluateAccelerations(f, s.x, s.v, s.inv_mass, s.external_force, a);
  if (!s.history_valid) {
    // Second-order start: x- = x - v dt + a dt^2/2 (Taylor backwards).
    for (std::size_t i = 0; i < n; ++i) s.x_prev[i] = s.x[i] - dt * s.v[i] + 0.5 * dt * dt * a[i];
  }
  // Drag needs the end-of-step velocity: (x+ - x)/dt + a dt/2 predicts it to O(dt^2), which
  // keeps the scheme second order with velocity-dependent forces.
  std::span<Vec3> v_est(vs_.data(), n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 next = 2.0 * s.x[i] - s.x_prev[i] + dt * dt * a[i];
    v_est[i] = (next - s.x[i]) / dt + 0.5 * dt * a[i];
    xs_[i] = next;
  }
  std::span<Vec3> a_next(a2_.data(), n);
  evaluateAccelerations(f, std::span<const Vec3>(xs_.data(), n), v_est, s.inv_mass,
                        s.external_force, a_next);
  for (std::size_t i = 0; i < n; ++i) {
    s.x_prev[i] = s.x[i];
    s.x_out[i] = xs_[i];
    s.v_out[i] = (xs_[i] - s.x[i]) / dt + 0.5 * dt * a_next[i];
  }
}

void LinearIntegrator::velocityVerlet(const ForceModel& f, const LinearStateView& s, double dt) {
  const std::size_t n = s.x.size();
  std::span<Vec3> a(a1_.data(), n);
  evaluateAccelerations(f, s.x, s.v, s.inv_mass, s.external_force, a);
  std::span<Vec3> v_pred(vs_.data(), n);
  for (std::size_t i = 0; i < n; ++i) {
    xs_[i] = s.x[i] + dt * s.v[i] + 0.5 * dt * dt * a[i];
    // Drag is evaluated at the Euler-predicted end velocity (O(dt^2) off), which keeps the
    // scheme second order; position-only forces do not see it.
    v_pred[i] = s.v[i] + dt * a[i];
  }
  std::span<Vec3> a_next(a2_.data(), n);
  evaluateAccelerations(f, std::span<const Vec3>(xs_.data(), n), v_pred, s.inv_mass,
                        s.external_force, a_next);
  for (std::size_t i = 0; i < n; ++i) {
    s.x_out[i] = xs_[i];
    s.v_out[i] = s.v[i] + 0.5 * dt * (a[i] + a_next[i]);
  }
}

void LinearIntegrator::rk2Midpoint(const ForceModel& f, const LinearStateView& s, double dt) {
  const std::size_t n = s.x.size();
  std::span<Vec3> a(a1_.data(), n);
  evaluateAccelerations(f, s.x, s.v, s.inv_mass, s.external_force, a);
  std::span<Vec3> v_mid(vs_.data(), n);
  for (std::size_t i = 0; i < n; ++i) {
    xs_[i] = s.x[i] + 0.5 * dt * s.v[i];
    v_mid[i] = s.v[i] + 0.5 * dt * a[i];
  }
  std::span<Vec3> a_mid(a2_.data(), n);
  evaluateAccelerations(f, std::span<const Vec3>(xs_.data(), n), v_mid, s.inv_mass,
                        s.external_force, a_mid);
  for (std::size_t i = 0; i < n; ++i) {
    s.x_out[i] = s.x[i] + dt * v_mid[i];
    s.v_out[i] = s.v[i] + dt * a_mid[i];
  }
}

void LinearIntegrator::rk4(const ForceModel& f, const LinearStateView& s, double dt) {
  const std::size_t n = s.x.size();
  const std::span<const Vec3> xs(xs_.data(), n);
  std::span<Vec3> k1(a1_.data(), n), k2(a2_.data(), n), k3(a3_.data(), n), k4(a4_.data(), n);
  // Stage velocities double as the position derivatives of stages 2-4.
  evaluateAccelerations(f, s.x, s.v, s.inv_mass, s.external_force, k1);
  for (std::size_t i = 0; i < n; ++i) {
    xs_[i] = s.x[i] + 0.5 * dt * s.v[i];
    v2_[i] = s.v[i] + 0.5 * dt * k1[i];
  }
  evaluateAccelerations(f, xs, std::span<const Vec3>(v2_.data(), n), s.inv_mass, s.external_force,
                        k2);
  for (std::size_t i = 0; i < n; ++i) {
    xs_[i] = s.x[i] + 0.5 * dt * v2_[i];
    v3_[i] = s.v[i] + 0.5 * dt * k2[i];
  }
  evaluateAccelerations(f, xs, std::span<const Vec3>(v3_.data(), n), s.inv_mass, s.external_force,
                        k3);
  for (std::size_t i = 0; i < n; ++i) {
    xs_[i] = s.x[i] + dt * v3_[i];
    v4_[i] = s.v[i] + dt * k3[i];
  }
  evaluateAccelerations(f, xs, std::span<const Vec3>(v4_.data(), n), s.inv_mass, s.external_force,
                        k4);
  for (std::size_t i = 0; i < n; ++i) {
    s.x_out[i] = s.x[i] + dt / 6.0 * (s.v[i] + 2.0 * v2_[i] + 2.0 * v3_[i] + v4_[i]);
    s.v_out[i] = s.v[i] + dt / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

}  // namespace zonesim::physics
