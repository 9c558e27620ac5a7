#include "zone_node/systems/rigid_bodies.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/scene.h"
#include "crowd/lod.h"
#include "physics/cloth.h"
#include "physics/cloth_collision.h"
#include "physics/mass_properties.h"
#include "physics/world.h"
#include "zone_node/ghost_store.h"
#include "zone_node/population.h"
#include "zone_node/systems/crowd_lod.h"
#include "zone_node/systems/scene_shapes.h"
#include "zone_node/tick_profile.h"

namespace zonesim::zone {

namespace {

physics::WorldSettings settingsFor(const PhysicsSettings& p, const CrowdLod& lod) {
  physics::WorldSettings w;
  w.lod_longest_step = lod.physics_max_step;
  w.integrator = physics::Integrator(int(p.integrator));
  w.broadphase = physics::BroadphaseKind(int(p.broadphase));
  w.substeps = p.substeps;
  w.gyroscopic = p.gyroscopic;
  w.solver.velocity_iterations = p.velocity_iterations;
  w.solver.position_iterations = p.position_iterations;
  w.sleep.enabled = p.sleep;
  w.solver.kind = physics::SolverKind(int(p.solver));
  w.solver.sor_omega = p.sor_omega;
  w.solver.joint_hertz = p.joint_hertz;
  w.solver.joint_damping_ratio = p.joint_damping_ratio;
  w.contact_recycle_distance = p.contact_recycle_distance;
  return w;
}

physics::Shape primitiveShape(const BodyData& b) {
  switch (b.shape) {
    case BodyData::Box:
      return physics::Shape::box(b.half_extents);
    case BodyData::Capsule:
      return physics::Shape::capsule(b.radius, b.half_height);
    default:
      return physics::Shape::sphere(b.radius);
  }
}

double volumeOf(const BodyData& b) {
  const double r = b.radius;
  switch (b.shape) {
    case BodyData::Box:
      return 8.0 * b.half_extents.prod();
    case BodyData::Capsule:
      return M_PI * r * r * (2.0 * b.half_height + 4.0 / 3.0 * r);
    default:
      return 4.0 / 3.0 * M_PI * r * r * r;
  }
}

/// A static half-space through `point` whose solid side is opposite `normal`.
physics::BodyDesc wall(const Vec3& point, const Vec3& normal) {
  physics::BodyDesc d;
  d.type = physics::BodyType::Static;
  d.shape = physics::Shape::plane();
  d.position = point;
  d.orientation = Quat::FromTwoVectors(Vec3::UnitY(), normal);
  return d;
}

physics::Cloth makeCloth(const SceneCloth& c) {
  physics::ClothDesc d;
  d.columns = c.columns;
  d.rows = c.rows;
  d.spacing = c.spacing;
  d.origin = toVec3(c.origin);
  d.column_axis = toVec3(c.column_axis);
  d.row_axis = toVec3(c.row_axis);
  d.particle_mass = c.particle_mass;
  d.stiffness = c.stiffness;
  d.shear_stiffness = c.shear_stiffness;
  d.bend_stiffness = c.bend_stiffness;
  d.spring_damping = c.damping;
  d.tear_strain = c.tear_strain;
  d.thickness = c.thickness;
  d.friction = c.friction;
  d.integrator = physics::ClothIntegrator(c.integrator);
  physics::Cloth cloth(d);
  for (auto [col, row] : c.pins) cloth.pin(cloth.index(col, row));
  return cloth;
}

/// Cloth sub-steps per tick: semi-implicit Euler is stable for h w < 2; a particle's stiffest
/// mode is bounded by w^2 = 8 (k + k_shear + k_bend) / m (every spring on it in phase), and
/// h w <= 0.5 keeps the drape's damping and sag close to the converged ones.
int substepsPerTick(const SceneCloth& c, double dt) {
  if (c.substeps > 0) return c.substeps;
  if (c.integrator == SceneCloth::Integrator::ImplicitEuler) return 1;  // stable at any step
  const double w =
      std::sqrt(8.0 * (c.stiffness + c.shear_stiffness + c.bend_stiffness) / c.particle_mass);
  return std::max(1, int(std::ceil(dt * w / 0.5)));
}

/// The impulse (N s at the centre) explosion e gives in tick k of length dt; 0 when none.
double explosionImpulse(const SceneExplosion& e, std::uint64_t k, double dt) {
  // The first tick starting at or after its time (1e-9 of a tick forgives round-off).
  const auto fire = std::uint64_t(std::max(0.0, std::ceil(e.time / dt - 1e-9)));
  if (k < fire) return 0;
  if (e.impulse > 0) return k == fire ? e.impulse : 0.0;
  const double left = e.duration - double(k - fire) * dt;
  if (left <= 1e-12) return 0;
  return e.force * std::min(dt, left);
}

}  // namespace

// The engine and its enums mirror the scene's (same order): checked here, where both are seen.
static_assert(int(physics::Integrator::Rk4) == int(PhysicsSettings::Integrator::Rk4));
static_assert(int(physics::BroadphaseKind::AabbTree) == int(PhysicsSettings::Broadphase::AabbTree));
static_assert(int(physics::SolverKind::Projection) == int(PhysicsSettings::Solver::Projection));
static_assert(int(physics::SolverKind::ConjugateGradient) ==
              int(PhysicsSettings::Solver::ConjugateGradient));
static_assert(int(physics::SolverKind::GaussSeidel) == int(PhysicsSettings::Solver::GaussSeidel));
static_assert(int(physics::SolverKind::SoftStepWide) == int(PhysicsSettings::Solver::SoftStepWide));

static_assert(int(physics::Falloff::Quadratic) == int(SceneExplosion::Falloff::Quadratic));
static_assert(int(physics::ClothIntegrator::ImplicitEuler) ==
              int(SceneCloth::Integrator::ImplicitEuler));
static_assert(int(BodyData::Capsule) == int(SceneBody::Shape::Capsule));
static_assert(int(BodyData::Compound) == int(SceneBody::Shape::Compound));

RigidBodySystem::RigidBodySystem(const Scene& scene, int rank)
    : scene_(scene),
      rank_(rank),
      set_pieces_(scene.physics),
      cloth_colliders_(std::make_unique<physics::ClothColliders>()) {
  for (std::size_t k = 0; k < scene.physics.bodies.size(); ++k) {
    const SceneBody& b = scene.physics.bodies[k];
    if (b.motion != SceneBody::Motion::Dynamic || b.shape != SceneBody::Shape::Compound) continue;
    physics::Shape shape = centredSceneCompound(b).shape;
    const double volume = physics::computeMassProperties(shape, 1.0).mass;
    compounds_.emplace(namedBodyId(scene, k), Compound{std::move(shape), volume});
  }
  for (const SceneJoint& j : scene.physics.joints) {
    // A joint to the world or to a set piece links nothing: statics join no island.
    if (j.b < 0 || set_pieces_.indexOf(std::size_t(j.a)) || set_pieces_.indexOf(std::size_t(j.b)))
      continue;
    const EntityId a = namedBodyId(scene, std::size_t(j.a)),
                   b = namedBodyId(scene, std::size_t(j.b));
    joint_links_.emplace_back(std::min(a, b), std::max(a, b));
    jointed_.insert(a.value);
    jointed_.insert(b.value);
  }
  for (const SceneCloth& c : scene.physics.cloths) {
    cloths_.push_back(std::make_unique<physics::Cloth>(makeCloth(c)));
    cloth_substeps_.push_back(substepsPerTick(c, scene.dt));
  }
}

RigidBodySystem::~RigidBodySystem() = default;

physics::Shape RigidBodySystem::shapeOf(EntityId id, const BodyData& b) const {
  if (b.shape != BodyData::Compound) return primitiveShape(b);
  auto it = compounds_.find(id);
  if (it == compounds_.end())
    throw std::runtime_error("rigid body " + toString(id) +
                             " is a compound but no compound of physics.bodies has its id");
  return it->second.shape;
}

physics::BodyDesc RigidBodySystem::descOf(EntityId id, const BodyData& b, const Vec3& pos,
                                          const Quat& rot, const Vec3& vel) const {
  physics::BodyDesc d;
  d.shape = shapeOf(id, b);
  const double volume = b.shape == BodyData::Compound ? compounds_.at(id).volume : volumeOf(b);
  d.position = pos;
  d.orientation = rot;
  d.linear_velocity = vel;
  d.angular_velocity = b.angular_velocity;
  d.density = b.mass / volume;
  d.friction = b.friction;
  d.rolling_resistance = b.rolling_resistance;
  d.restitution = b.restitution;
  d.linear_damping = b.linear_damping;
  d.angular_damping = b.angular_damping;
  return d;
}

void RigidBodySystem::rebuild(const std::vector<BodyRef>& bodies) {
  world_ = std::make_unique<physics::World>(settingsFor(scene_.physics, scene_.lod));
  world_->forces().linear_drag = scene_.physics.linear_drag;
  world_->forces().quadratic_drag = scene_.physics.quadratic_drag;
  const SceneBox& w = scene_.world;
  world_->addBody(wall(Vec3(0, w.min.y, 0), Vec3::UnitY()));
  world_->addBody(wall(Vec3(w.min.x, 0, 0), Vec3::UnitX()));
  world_->addBody(wall(Vec3(w.max.x, 0, 0), -Vec3::UnitX()));
  world_->addBody(wall(Vec3(0, 0, w.min.z), Vec3::UnitZ()));
  world_->addBody(wall(Vec3(0, 0, w.max.z), -Vec3::UnitZ()));
  set_pieces_.addTo(*world_);
  first_dynamic_ = physics::BodyIndex(5 + set_pieces_.count());
  body_entity_.clear();
  members_ = {};
  // In id order, so the engine sees the same body order whichever rank holds them.
  for (const BodyRef& r : bodies) {
    const EntityStore& s = *r.store;
    const std::size_t i = r.index;
    const physics::BodyIndex bi =
        world_->addBody(descOf(s.id[i], s.body[i], s.pos[i], s.rot[i], s.vel[i]));
    // Exactly the engine's own orientation: normalising it again would move the last bit, and
    // a rebuilt world must step a body as the old one would have.
    world_->bodies().orientation[bi] = s.rot[i];
    world_->setStepLag(bi, s.body[i].step_lag);  // owed ticks survive the rebuild
    body_entity_.push_back(s.id[i]);
    members_.add(s.id[i]);
  }
  world_->bodies().updateWorldInertia();
  addJoints();
  ++rebuilds_;
}

void RigidBodySystem::addJoints() {
  joints_added_ = 0;
  joint_slots_.clear();
  const std::vector<SceneBody>& named = scene_.physics.bodies;
  auto bodyOf = [&](int k) -> std::optional<physics::BodyIndex> {
    if (auto piece = set_pieces_.indexOf(std::size_t(k))) return piece;
    EntityId id = namedBodyId(scene_, std::size_t(k));
    auto it = std::find(body_entity_.begin(), body_entity_.end(), id);
    if (it == body_entity_.end()) return std::nullopt;
    return physics::BodyIndex(first_dynamic_ + (it - body_entity_.begin()));
  };
  for (std::size_t k = 0; k < scene_.physics.joints.size(); ++k) {
    const SceneJoint& j = scene_.physics.joints[k];
    std::optional<physics::BodyIndex> a = bodyOf(j.a);
    std::optional<physics::BodyIndex> b = j.b >= 0 ? bodyOf(j.b) : physics::kNoBody;
    if (!a || !b) continue;  // a body is gone (quarantined, or never here)
    // Anchors in the bodies' frames at the scene's start poses, so a rebuild later in the run
    // keeps the same joint.
    const Vec3 pa = entityStart(named[j.a]);
    const Vec3 pb = j.b >= 0 ? entityStart(named[j.b]) : Vec3::Zero();
    const Quat qa = toQuat(named[j.a].orientation);
    const Quat qb = j.b >= 0 ? toQuat(named[j.b].orientation) : Quat::Identity();
    auto local_a = [&](const SceneVec3& p) -> Vec3 { return qa.conjugate() * (toVec3(p) - pa); };
    auto local_b = [&](const SceneVec3& p) -> Vec3 { return qb.conjugate() * (toVec3(p) - pb); };
    // Its first dynamic body keeps its warm start (the other may be a set piece or the world).
    JointSlot slot{int(k), int(j.type), 0, *a >= first_dynamic_ ? *a : *b};
    switch (j.type) {
      case SceneJoint::Type::Distance: {
        physics::DistanceJoint d;
        d.a = *a;
        d.b = *b;
        d.local_a = local_a(j.anchor_a);
        d.local_b = local_b(j.anchor_b);
        d.length = j.length;
        slot.index = world_->addDistanceJoint(d);
        break;
      }
      case SceneJoint::Type::Ball: {
        physics::BallJoint d;
        d.a = *a;
        d.b = *b;
        d.local_a = local_a(j.anchor);
        d.local_b = local_b(j.anchor);
        slot.index = world_->addBallJoint(d);
        break;
      }
      case SceneJoint::Type::Hinge: {
        physics::HingeJoint d;
        d.a = *a;
        d.b = *b;
        d.local_a = local_a(j.anchor);
        d.local_b = local_b(j.anchor);
        d.axis_a = qa.conjugate() * toVec3(j.axis);
        d.axis_b = qb.conjugate() * toVec3(j.axis);
        slot.index = world_->addHingeJoint(d);
        break;
      }
    }
    if (!j.collide) world_->ignoreContactsBetween(*a, *b);
    joint_slots_.push_back(slot);
    ++joints_added_;
  }
}

bool RigidBodySystem::explosionDue(std::uint64_t k, double dt) const {
  for (const SceneExplosion& e : scene_.physics.explosions)
    if (explosionImpulse(e, k, dt) > 0) return true;
  return false;
}

bool RigidBodySystem::explode(std::uint64_t k, double dt) {
  bool acted = false;
  physics::BodyStorage& s = world_->bodies();
  for (const SceneExplosion& e : scene_.physics.explosions) {
    const double impulse = explosionImpulse(e, k, dt);
    if (impulse == 0) continue;
    const Vec3 centre = toVec3(e.position);
    for (std::size_t n = 0; n < body_entity_.size(); ++n) {
      auto i = physics::BodyIndex(first_dynamic_ + n);
      if (s.inv_mass[i] == 0.0) continue;  // frozen
      const Vec3 d = s.position[i] - centre;
      const double r = d.norm();
      if (r == 0.0 || r >= e.radius) continue;
      const double j =
          impulse * physics::falloffFactor(physics::Falloff(int(e.falloff)), r, e.radius);
      s.linear_velocity[i] += (s.inv_mass[i] * j / r) * d;
      world_->wake(i);
      acted = true;
    }
  }
  return acted;
}

void RigidBodySystem::stepCloths(double dt) {
  if (cloths_.empty()) return;
  cloth_colliders_->gather(world_->bodies());
  for (std::size_t c = 0; c < cloths_.size(); ++c)
    cloths_[c]->step(dt, cloth_substeps_[c], cloth_colliders_.get());
  cloth_colliders_->applyReactions(*world_);
}

void RigidBodySystem::step(StepContext& ctx) {
  profile_ = {};
  border_time_ = 0;
  bodies_held_ = 0;
  const std::uint64_t steps_before = world_steps_;
  ctx.counters.bodies_awake = ctx.cluster.swap ? advanceInCluster(ctx) : advanceAlone(ctx);
  ctx.counters.physics_steps = world_steps_ - steps_before;
  ctx.counters.bodies_held = bodies_held_;
}

void RigidBodySystem::setStepPeriods(std::span<const crowd::Vec2> players) {
  const crowd::LodSettings lod = lodOf(scene_.lod);
  const physics::BodyStorage& s = world_->bodies();
  for (std::size_t n = 0; n < body_entity_.size(); ++n) {
    const auto bi = physics::BodyIndex(first_dynamic_ + n);
    const crowd::Vec2 at{s.position[bi].x(), s.position[bi].z()};
    const bool near = crowd::lodLevel(at, players, lod) == crowd::LodLevel::Near;
    world_->setStepPeriod(bi, near ? 1 : scene_.lod.physics_every);
  }
}

std::vector<std::size_t> RigidBodySystem::bodiesById(const EntityStore& store) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.kind[i] == EntityKind::RigidBody) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return store.id[a] < store.id[b]; });
  return order;
}

std::size_t RigidBodySystem::advanceAlone(StepContext& ctx) {
  // The same bodies as on a tick that found them all asleep, and nothing that could wake one:
  // that tick's answer holds without looking at the store again (issue 19's idle cost).
  if (world_ && resting_membership_ == ctx.store.membership() && cloths_.empty() &&
      !set_pieces_.moving() && !explosionDue(ctx.tick, ctx.dt))
    return 0;
  resting_membership_.reset();
  std::vector<BodyRef> bodies;
  for (std::size_t i : bodiesById(ctx.store)) bodies.push_back({&ctx.store, i});
  ctx.counters.bodies_checked = bodies.size();
  if (bodies.empty() && cloths_.empty()) {
    world_.reset();
    members_ = {};
    return 0;
  }
  holdBodies(bodies, false);
  if (!stepWorld(ctx) && !holdsCloths(ctx)) {
    resting_membership_ = ctx.store.membership();
    return 0;
  }
  return writeBack(bodies, false);
}

void RigidBodySystem::holdBodies(const std::vector<BodyRef>& bodies, bool carried) {
  IdSetDigest now;
  for (const BodyRef& r : bodies) now.add(r.id());
  if (world_ && now == members_) return;
  rebuild(bodies);
  if (carried) importCarried(bodies);
}

bool RigidBodySystem::stepWorld(StepContext& ctx) {
  set_pieces_.pose(*world_, ctx.tick, ctx.dt);
  explode(ctx.tick, ctx.dt);
  // Sleeping bodies are not stepped at all; the statics count as asleep in the engine or not,
  // so compare the dynamic bodies' state directly. A moving kinematic body may wake them.
  std::size_t awake = 0;
  for (std::size_t n = 0; n < body_entity_.size(); ++n)
    awake += !world_->asleep(physics::BodyIndex(first_dynamic_ + n));
  const bool stepped = awake > 0 || set_pieces_.moving();
  if (stepped) {
    std::size_t frozen_before = world_->quarantined().size();
    if (scene_.lod.enabled && scene_.lod.physics_every > 1) setStepPeriods(ctx.players);
    // Numbered by the tick, so far islands step on the same ticks whichever world holds them.
    world_->setStepNumber(ctx.tick);
    world_->step(ctx.dt);
    ++world_steps_;
    profile_ = world_->profile();
    quarantined_ += world_->quarantined().size() - frozen_before;
  }
  if (holdsCloths(ctx)) stepCloths(ctx.dt);
  return stepped;
}

std::size_t RigidBodySystem::writeBack(const std::vector<BodyRef>& bodies, bool carried) {
  const physics::BodyStorage& s = world_->bodies();
  std::size_t awake = 0;
  for (std::size_t n = 0; n < bodies.size(); ++n) {
    const auto bi = physics::BodyIndex(first_dynamic_ + n);
    EntityStore& store = *bodies[n].store;
    const std::size_t i = bodies[n].index;
    store.pos[i] = s.position[bi];
    store.vel[i] = s.linear_velocity[bi];
    store.rot[i] = s.orientation[bi];
    store.body[i].angular_velocity = s.angular_velocity[bi];
    store.body[i].sleeping = world_->asleep(bi);
    awake += !store.body[i].sleeping;
    store.body[i].step_lag = world_->stepLod().lag(bi);
    bodies_held_ += store.body[i].step_lag > 0;
  }
  if (carried) exportCarried(bodies);
  return awake;
}

}  // namespace zonesim::zone
