#pragma once
// The physics world: bodies, forces and the step pipeline
//   forces -> integrate velocities -> broadphase -> narrowphase -> contact solve (velocities,
//   then split-impulse positions) -> integrate positions -> non-finite check.

#include <cstdint>
#include <span>
#include <vector>

#include "physics/body_storage.h"
#include "physics/broadphase.h"
#include "physics/contact_events.h"
#include "physics/contact_solver.h"
#include "physics/distance_joints.h"
#include "physics/forces.h"
#include "physics/integrator.h"
#include "physics/islands.h"
#include "physics/rigid_joints.h"
#include "physics/step_lod.h"
#include "physics/step_profile.h"
#include "physics/wide_contact_solver.h"

namespace zonesim::physics {

/// Every approximation of the world step, selectable per scene.
struct WorldSettings {
  Integrator integrator = Integrator::SemiImplicitEuler;
  BroadphaseKind broadphase = BroadphaseKind::SweepAndPrune;
  /// m: the broadphase keeps the pairs of boxes grown by this much between steps and looks
  /// again only at bodies that left their grown box (0: all pairs anew every step). The pairs
  /// found are the same either way.
  double broadphase_keep_margin = 0.1;
  SolverSettings solver;
  int substeps = 1;
  double contact_margin = 0.02;  ///< m: contacts are kept this far before touching.
  /// Baumgarte fraction of a joint's length error removed per step.
  double joint_beta = 0.2;
  /// Grow each body's contact search by its travel this step: speculative contacts stop fast
  /// bodies at thin walls without continuous collision detection.
  bool speculative = true;
  /// Islands at rest fall asleep (off by default, as in the benchmark scenes).
  SleepSettings sleep;
  /// The gyroscopic term of Euler's equations, I dw/dt = -w x I w: a body spinning off a
  /// principal axis precesses and keeps its angular momentum, instead of keeping its angular
  /// velocity. Taken implicitly (one Newton step, stable at any spin). Off by default: the
  /// shipped scenes were measured without it.
  bool gyroscopic = false;
  /// Level of detail: the longest step (s) a held island may take when its turn comes; its
  /// period is cut to fit, and a longer debt is paid in several steps. Stacks fall apart in
  /// long steps (a 10-level pyramid drifts 6 cm at 1/15 s per step and flies apart at 2/15 s;
  /// docs/benchmarks.md). 0: no limit.
  double lod_longest_step = 0.0;
  /// Contact recycling (m; 0: off): a touching pair whose bodies moved less than this relative
  /// to each other since its manifold was computed, and neither turned more than about 11.5
  /// degrees, keeps the manifold, carried along with the bodies, instead of running the
  /// narrowphase (physics/contact_recycling.h). A pair is recycled only while it certainly
  /// stays within the contact margin, so contactEvents() are the narrowphase's own. Only pairs
  /// with a box are recycled (others collide in fewer operations than the test takes), and
  /// compound pairs never. Off by default: the shipped scenes were measured without it.
  double contact_recycle_distance = 0.0;
  /// Keep contactEvents(): the pairs that began and ended touching each step (a merge of the
  /// contact list per step, so off unless asked for).
  bool contact_events = false;
};

/// A world's contacts as warm starts, to carry into another world (World::warmStarts).
struct WarmStarts {
  std::vector<BodyContact> contacts;    ///< Sorted by body pair.
  std::vector<ManifoldOrigin> origins;  ///< What the contacts' origin fields index.
};

/// A set of bodies stepped together.
class World {
 public:
  /// A world with the given settings and default forces (gravity -9.81 y).
  explicit World(const WorldSettings& settings = {});

  /// Adds a body and returns its index.
  BodyIndex addBody(const BodyDesc& desc);
  /// Advances by dt, split into settings().substeps equal substeps. Islands whose bodies all
  /// have a step period k > 1 (setStepPeriod) step only on every k-th call, by the time they
  /// skipped, and are held still, as immovable obstacles, in between.
  void step(double dt);
  /// Level of detail in time: body i may step every `period` calls of step() (1-64; 1, the
  /// default, every call). Its island steps as often as its most often stepped body.
  void setStepPeriod(BodyIndex i, int period) { lod_.setPeriod(i, period); }
  /// Restores the steps body i was held and still owes (StepLod::lag), for a world rebuilt
  /// around bodies another world held: it then pays them as the old one would have.
  void setStepLag(BodyIndex i, int lag) { lod_.setLag(i, lag); }
  /// Numbers the next step() call: islands of period k step on calls numbered a multiple of
  /// k, so a rebuilt world keeps the old one's phase (a zone numbers them by its tick).
  void setStepNumber(std::uint64_t n) { steps_ = n; }
  /// Step periods, what each body still owes, and the body steps taken and held so far.
  const StepLod& stepLod() const { return lod_; }

  /// Adds a force through the centre of mass for the next step (wakes the body).
  void applyForce(BodyIndex i, const Vec3& force) {
    islands_.wake(i);
    bodies_.force[i] += force;
  }
  /// Adds a torque for the next step (wakes the body).
  void applyTorque(BodyIndex i, const Vec3& torque) {
    islands_.wake(i);
    bodies_.torque[i] += torque;
  }
  /// An instantaneous explosion: every dynamic body whose centre lies within radius gets the
  /// impulse (N s, times the falloff) away from the centre through its centre of mass, and
  /// wakes. For a blast that lasts, add a Blast to forces().blasts.
  void applyExplosionImpulse(const Vec3& centre, double impulse, double radius, Falloff falloff);
  /// Adds a distance joint (solved with the contacts) and returns its index.
  std::uint32_t addDistanceJoint(const DistanceJoint& joint) { return joints_.add(joint); }
  /// Adds a ball-and-socket joint and returns its index among the ball joints.
  std::uint32_t addBallJoint(const BallJoint& joint) { return rigid_joints_.addBall(joint); }
  /// Adds a hinge joint and returns its index among the hinges.
  std::uint32_t addHingeJoint(const HingeJoint& joint) { return rigid_joints_.addHinge(joint); }
  /// Joint values carried from one step to the next (distance joint i; ball i; hinge i), to
  /// carry a joint into another world holding it, as warmStarts() does contacts.
  double distanceJointWarmStart(std::uint32_t i) const { return joints_.joints()[i].impulse; }
  void setDistanceJointWarmStart(std::uint32_t i, double impulse) {
    joints_.setImpulse(i, impulse);
  }
  std::array<double, RigidJoints::kWarmValues> ballJointWarmStart(std::uint32_t i) const {
    return rigid_joints_.warmState(i);
  }
  void setBallJointWarmStart(std::uint32_t i,
                             const std::array<double, RigidJoints::kWarmValues>& v) {
    rigid_joints_.setWarmState(i, v);
  }
  std::array<double, RigidJoints::kWarmValues> hingeJointWarmStart(std::uint32_t i) const {
    return rigid_joints_.warmState(rigid_joints_.ballCount() + i);
  }
  void setHingeJointWarmStart(std::uint32_t i,
                              const std::array<double, RigidJoints::kWarmValues>& v) {
    rigid_joints_.setWarmState(rigid_joints_.ballCount() + i, v);
  }
  /// Bodies a and b never touch: their pair gets no contact. For jointed neighbours whose shapes
  /// overlap at the joint (chain links, ragdoll limbs), as Box2D's collideConnected = false.
  void ignoreContactsBetween(BodyIndex a, BodyIndex b);
  /// Wakes body i and the island it sleeps in; call after setting a velocity by hand.
  void wake(BodyIndex i) { islands_.wake(i); }
  /// True when body i sleeps.
  bool asleep(BodyIndex i) const { return islands_.asleep(i); }
  /// Number of sleeping bodies.
  std::size_t sleepingCount() const { return islands_.sleepingCount(); }
  /// Body i's sleep (asleep, rest time, island), to carry into another world.
  SleepState sleepState(BodyIndex i) const { return islands_.state(i); }
  /// Sets body i's sleep, as sleepState() gave it (the group renamed to this world's index of
  /// the island's root body).
  void setSleepState(BodyIndex i, const SleepState& s) { islands_.setState(i, s); }

  /// What the next step warm-starts from, sorted by body pair: the last substep's contacts and
  /// those of sleeping islands (kept while they sleep, so that an island wakes warm).
  void warmStarts(WarmStarts& out) const;
  /// Makes `warm` (contacts sorted by body pair, indices of this world) what the next step
  /// warm-starts from, as if a step had found them: a world rebuilt with the same bodies in the
  /// same order then steps as the old one would have. contacts() returns them until that step.
  /// A contact whose origin is not an index of warm.origins is kept without one.
  void setWarmStarts(const WarmStarts& warm);

  /// Body state (read and write between steps).
  BodyStorage& bodies() { return bodies_; }
  /// Body state.
  const BodyStorage& bodies() const { return bodies_; }
  /// Gravity, drag and springs.
  ForceModel& forces() { return forces_; }
  /// Gravity, drag and springs.
  const ForceModel& forces() const { return forces_; }
  /// The settings in use.
  const WorldSettings& settings() const { return settings_; }
  /// The contacts found and solved in the last substep, sorted by body pair.
  std::span<const BodyContact> contacts() const { return contacts_; }
  /// The manifold origins that contacts()' origin fields index (contact recycling).
  std::span<const ManifoldOrigin> contactOrigins() const { return origins_; }
  /// Bodies frozen because their state became non-finite, in the order found.
  std::span<const BodyIndex> quarantined() const { return quarantined_; }
  /// Time of each stage of the last step().
  const StepProfile& profile() const { return profile_; }
  /// Pairs that began and ended touching (a contact within the margin, awake or asleep) in the
  /// last step(); empty unless WorldSettings::contact_events.
  const ContactEvents& contactEvents() const { return events_; }
  /// Contacts the last step() recycled (carried along) and computed with the narrowphase.
  std::size_t recycledContacts() const { return recycled_; }
  std::size_t computedContacts() const { return computed_; }

 private:
  /// Every awake body advances by dt.
  void stepAll(double dt);
  /// The step with periods: one stepAll per step length of the due islands, the rest held.
  void stepLevels(double dt);
  /// Holds every awake movable body outside pass p still (no mass, no velocity) and sets aside
  /// the contacts that pass will not see again; releaseHeld() undoes both.
  void holdAllBut(int pass, int ticks);
  void releaseHeld();
  /// Asleep, or held by the level of detail: not integrated and not paired with other still
  /// bodies.
  bool still(BodyIndex i) const { return islands_.asleep(i) || (!held_.empty() && held_[i]); }
  void substep(double dt);
  void integrateForces(double dt);
  /// The angular velocity of dynamic body i after dt of its gyroscopic torque (implicit).
  Vec3 gyroscopicStep(BodyIndex i, const Vec3& w, double dt) const;
  /// Broadphase then narrowphase, each timed.
  void findContacts(double dt);
  void findPairs(double dt);
  void contactsOfPairs(double dt);
  void addContact(BodyIndex a, BodyIndex b, double margin);
  /// Carries the pair's last manifold into contacts_ when contact recycling allows; false
  /// when the narrowphase must run.
  bool recycleContact(BodyIndex a, BodyIndex b, const Pose& pa, const Pose& pb, double margin);
  bool contactIgnored(BodyIndex a, BodyIndex b) const;
  void wakeTouched();
  /// previous_ += the sleeping islands' contacts; keeps those whose bodies still rest.
  void carrySleepingContacts();
  /// Moves the origins of the contacts kept aside (asleep, held) from previous_origins_ to
  /// origins_, where the new contacts' are.
  void keepOrigins(std::vector<BodyContact>& kept);
  void warmStartFromPrevious();
  void integratePositions(double dt);
  /// The soft step's springs and sub-steps for a step of dt (SoftStep and SoftStepWide).
  struct SoftSprings {
    int substeps;
    double h;
    Softness contact, contact_fixed, joint;
  };
  SoftSprings softSprings(double dt) const;
  void solveSoftStep(double dt);
  /// SoftStepWide (world_soft_wide.cpp).
  void solveSoftStepWide(double dt);
  /// soft_touched_: 1 for each body under a contact or joint this step (the soft steps move
  /// those as their sub-steps did, and free bodies as the integrator did).
  void markConstrainedBodies();
  /// Wide soft step with joints: the solver bodies' velocities to and from bodies_.
  void exportWideVelocities();
  void importWideVelocities();
  void warmStartJoints();
  void iterateJoints();
  void iterateJointsSoft(const Softness& soft, bool use_bias);
  void solveIterative(double dt);
  void solveProjection(double dt);
  void quarantineNonFinite();

  WorldSettings settings_;
  BodyStorage bodies_;
  ForceModel forces_;
  LinearIntegrator integrator_;
  Broadphase broadphase_;
  ContactSolver solver_;
  WideContactSolver wide_solver_;
  SolverBodies wide_bodies_;
  Islands islands_;
  DistanceJoints joints_;
  RigidJoints rigid_joints_;

  // Per-step buffers, kept to avoid allocating in the step.
  std::vector<Vec3> x_start_, v_start_, x_force_, v_force_;
  std::vector<Vec3> soft_dp_, soft_dtheta_, soft_dv_;
  std::vector<std::uint8_t> soft_touched_;
  std::vector<Aabb> proxy_boxes_;
  std::vector<std::uint8_t> proxy_moving_;
  std::vector<BodyIndex> proxy_body_, planes_;
  std::vector<ProxyPair> pairs_;
  std::vector<std::uint64_t> ignored_pairs_;  // sorted keys (lower index << 32 | higher index)
  std::vector<BodyContact> contacts_, previous_;
  // The origins of contacts_, sleeping_contacts_ and held_contacts_ (their origin fields index
  // origins_), and of previous_ while contactsOfPairs builds the next ones.
  std::vector<ManifoldOrigin> origins_, previous_origins_;
  // Contacts of sleeping islands (not found while they sleep), kept for their warm start.
  std::vector<BodyContact> sleeping_contacts_, warm_source_;
  std::vector<BodyIndex> quarantined_;
  StepProfile profile_;
  ContactEvents events_;
  // Each body's bounding radius about its origin, for contact recycling.
  std::vector<double> bounding_radius_;
  std::size_t recycled_ = 0, computed_ = 0;
  std::size_t recycle_cursor_ = 0;  // where in previous_ the next pair is looked for first

  // Level of detail in time (step_lod.h) and what holding a body still set aside.
  StepLod lod_;
  std::uint64_t steps_ = 0;
  std::vector<std::uint8_t> held_, stepped_;
  std::vector<BodyIndex> held_list_;
  std::vector<double> held_inv_mass_;
  std::vector<Eigen::Matrix3d> held_inv_inertia_local_, held_inv_inertia_world_;
  std::vector<Vec3> held_linear_velocity_, held_angular_velocity_;
  std::vector<BodyContact> held_contacts_, merged_contacts_;
};

}  // namespace zonesim::physics
