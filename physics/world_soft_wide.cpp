// World::solveSoftStepWide: the soft step's sub-step loop (World::solveSoftStep) on the wide
// solver's float copy of the bodies. Joints are still solved in double on BodyStorage: where a
// world has any, the velocities go over to it and back around each joint pass.

#include <algorithm>

#include "physics/soft_joint_anchor.h"
#include "physics/world.h"

namespace zonesim::physics {

namespace {

void setMotion(SolverMotion& m, const Vec3& linear, const Vec3& angular) {
  for (int k = 0; k < 3; ++k) {
    m.linear[k] = static_cast<float>(linear[k]);
    m.angular[k] = static_cast<float>(angular[k]);
  }
}

Vec3 linearOf(const SolverMotion& m) {
  return Vec3(m.linear[0], m.linear[1], m.linear[2]);
}
Vec3 angularOf(const SolverMotion& m) {
  return Vec3(m.angular[0], m.angular[1], m.angular[2]);
}

}  // namespace

void World::exportWideVelocities() {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.type[i] == BodyType::Static) continue;
    bodies_.linear_velocity[i] = linearOf(wide_bodies_.velocity[i]);
    bodies_.angular_velocity[i] = angularOf(wide_bodies_.velocity[i]);
  }
}

void World::importWideVelocities() {
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    setMotion(wide_bodies_.velocity[i], bodies_.linear_velocity[i], bodies_.angular_velocity[i]);
  }
}

void World::solveSoftStepWide(double dt) {
  const SoftSprings springs = softSprings(dt);
  const double h = springs.h;
  const std::size_t n = bodies_.size();
  SolverBodies& state = wide_bodies_;
  state.reset(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool moves = bodies_.type[i] != BodyType::Static;
    setMotion(state.velocity[i], moves ? v_start_[i] : bodies_.linear_velocity[i],
              bodies_.angular_velocity[i]);
    // The force-driven velocity change is spread over the sub-steps.
    setMotion(state.velocity_step[i], (v_force_[i] - v_start_[i]) / springs.substeps, Vec3::Zero());
  }
  const bool has_joints = !joints_.joints().empty() || !rigid_joints_.empty();
  const auto jointPass = [&](bool use_bias) {
    if (!has_joints) return;
    exportWideVelocities();
    iterateJointsSoft(springs.joint, use_bias);
    importWideVelocities();
  };
  const int relax_passes = std::max(1, settings_.solver.position_iterations);
  const auto inv_h = 1.0 / h;
  const auto hf = static_cast<float>(h);
  for (int sub = 0; sub < springs.substeps; ++sub) {
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k < 3; ++k) state.velocity[i].linear[k] += state.velocity_step[i].linear[k];
    }
    if (has_joints) {
      soft_dp_.resize(n);
      soft_dtheta_.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        soft_dp_[i] = linearOf(state.displacement[i]);
        soft_dtheta_[i] = angularOf(state.displacement[i]);
      }
      exportWideVelocities();
      // Preparing warm-starts the joints on the bodies' velocities.
      joints_.prepareSoft(bodies_, soft_dp_, soft_dtheta_);
      rigid_joints_.prepareSoft(bodies_, soft_dp_, soft_dtheta_);
      importWideVelocities();
    }
    wide_solver_.warmStart(state);
    jointPass(true);
    wide_solver_.solve(state, springs.contact, springs.contact_fixed, true, inv_h);
    for (std::size_t i = 0; i < n; ++i) {
      SolverMotion& d = state.displacement[i];
      const SolverMotion& v = state.velocity[i];
      for (int k = 0; k < 3; ++k) {
        d.linear[k] += hf * v.linear[k];
        d.angular[k] += hf * v.angular[k];
      }
    }
    for (int r = 0; r < relax_passes; ++r) {
      jointPass(false);
      wide_solver_.solve(state, springs.contact, springs.contact_fixed, false, inv_h);
    }
  }
  wide_solver_.applyRestitution(state);
  wide_solver_.storeImpulses(contacts_);
  // As the soft step: a body under a constraint moves as the sub-steps moved it, a free body
  // keeps the integrator's motion (and its double velocity).
  markConstrainedBodies();
  for (std::size_t i = 0; i < n; ++i) {
    const BodyType type = bodies_.type[i];
    if (type == BodyType::Static || still(BodyIndex(i))) continue;
    if (!soft_touched_[i]) {
      bodies_.linear_velocity[i] = v_force_[i];
      bodies_.position[i] = x_force_[i];
      if (type != BodyType::Particle) {
        bodies_.orientation[i] =
            rotatedBy(dt * bodies_.angular_velocity[i], bodies_.orientation[i]);
      }
      continue;
    }
    bodies_.linear_velocity[i] = linearOf(state.velocity[i]);
    bodies_.position[i] = x_start_[i] + linearOf(state.displacement[i]);
    if (type == BodyType::Particle) continue;
    bodies_.angular_velocity[i] = angularOf(state.velocity[i]);
    // Turned by exactly the rotation the sub-steps integrated (soft_joint_anchor.h).
    bodies_.orientation[i] = rotatedBy(angularOf(state.displacement[i]), bodies_.orientation[i]);
  }
}

}  // namespace zonesim::physics
