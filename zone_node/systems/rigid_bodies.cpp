#include "zone_node/systems/rigid_bodies.h"

#include <algorithm>

#include "zone_node/cluster/ghost_store.h"
#include "zone_node/physics/world.h"

namespace zonesim::zone {

namespace {

physics::WorldSettings settingsFor(const PhysicsSettings& p) {
  physics::WorldSettings w;
  w.integrator = physics::Integrator(int(p.integrator));
  w.broadphase = physics::BroadphaseKind(int(p.broadphase));
  w.substeps = p.substeps;
  w.solver.velocity_iterations = p.velocity_iterations;
  w.solver.position_iterations = p.position_iterations;
  w.sleep.enabled = p.sleep;
  w.solver.kind = physics::SolverKind(int(p.solver));
  w.solver.sor_omega = p.sor_omega;
  return w;
}

physics::Shape shapeOf(const BodyData& b) {
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

}  // namespace

// The engine and its enums mirror the scene's (same order): checked here, where both are seen.
static_assert(int(physics::Integrator::Rk4) == int(PhysicsSettings::Integrator::Rk4));
static_assert(int(physics::BroadphaseKind::AabbTree) == int(PhysicsSettings::Broadphase::AabbTree));
static_assert(int(physics::SolverKind::Projection) == int(PhysicsSettings::Solver::Projection));
static_assert(int(physics::SolverKind::GaussSeidel) == int(PhysicsSettings::Solver::GaussSeidel));

RigidBodySystem::RigidBodySystem(const Scene& scene, int rank) : scene_(scene), rank_(rank) {}

RigidBodySystem::~RigidBodySystem() = default;

static physics::BodyDesc descOf(const BodyData& b, const Vec3& pos, const Quat& rot,
                                const Vec3& vel) {
  physics::BodyDesc d;
  d.shape = shapeOf(b);
  d.position = pos;
  d.orientation = rot;
  d.linear_velocity = vel;
  d.angular_velocity = b.angular_velocity;
  d.density = b.mass / volumeOf(b);
  d.friction = b.friction;
  d.restitution = b.restitution;
  return d;
}

std::vector<std::size_t> RigidBodySystem::foreignBodies(const GhostStore* ghosts) const {
  std::vector<std::size_t> out;
  if (!ghosts) return out;
  for (std::size_t g = 0; g < ghosts->size(); ++g)
    if (ghosts->kind[g] == EntityKind::RigidBody && ghosts->owner[g] > rank_) out.push_back(g);
  std::sort(out.begin(), out.end(), [&](auto a, auto b) { return ghosts->id[a] < ghosts->id[b]; });
  return out;
}

void RigidBodySystem::rebuild(const EntityStore& store, const GhostStore* ghosts,
                              const std::vector<std::size_t>& foreign) {
  world_ = std::make_unique<physics::World>(settingsFor(scene_.physics));
  const SceneBox& w = scene_.world;
  world_->addBody(wall(Vec3(0, w.min.y, 0), Vec3::UnitY()));
  world_->addBody(wall(Vec3(w.min.x, 0, 0), Vec3::UnitX()));
  world_->addBody(wall(Vec3(w.max.x, 0, 0), -Vec3::UnitX()));
  world_->addBody(wall(Vec3(0, 0, w.min.z), Vec3::UnitZ()));
  world_->addBody(wall(Vec3(0, 0, w.max.z), -Vec3::UnitZ()));
  first_dynamic_ = 5;
  body_entity_.clear();
  members_ = {};
  // In id order, so the engine sees the same body order whichever rank holds them.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.kind[i] == EntityKind::RigidBody) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return store.id[a] < store.id[b]; });
  for (std::size_t i : order) {
    world_->addBody(descOf(store.body[i], store.pos[i], store.rot[i], store.vel[i]));
    body_entity_.push_back(store.id[i]);
    members_.add(store.id[i]);
  }
  foreign_entity_.clear();
  for (std::size_t g : foreign) {
    physics::BodyDesc d = descOf(ghosts->body[g], ghosts->pos[g], ghosts->rot[g], ghosts->vel[g]);
    d.foreign = true;
    world_->addBody(d);
    foreign_entity_.push_back(ghosts->id[g]);
  }
  ++rebuilds_;
}

std::size_t RigidBodySystem::step(EntityStore& store, const GhostStore* ghosts, double dt) {
  ghost_impulses_.clear();
  IdSetDigest now;
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.kind[i] == EntityKind::RigidBody) now.add(store.id[i]);
  if (now.count == 0) {
    world_.reset();
    members_ = {};
    foreign_entity_.clear();
    return 0;
  }
  std::vector<std::size_t> foreign = foreignBodies(ghosts);
  bool same_foreign = foreign.size() == foreign_entity_.size();
  for (std::size_t k = 0; same_foreign && k < foreign.size(); ++k)
    same_foreign = ghosts->id[foreign[k]] == foreign_entity_[k];
  if (!world_ || !(now == members_) || !same_foreign) rebuild(store, ghosts, foreign);
  std::size_t bodies = body_entity_.size();
  const auto first_foreign = physics::BodyIndex(first_dynamic_ + bodies);

  // Foreign bodies take their owners' state of this tick.
  physics::BodyStorage& s = world_->bodies();
  bool foreign_awake = false;
  for (std::size_t k = 0; k < foreign.size(); ++k) {
    std::size_t g = foreign[k];
    auto bi = physics::BodyIndex(first_foreign + k);
    s.position[bi] = ghosts->pos[g];
    s.position_prev[bi] = ghosts->pos[g];
    s.orientation[bi] = ghosts->rot[g];
    s.linear_velocity[bi] = ghosts->vel[g];
    s.angular_velocity[bi] = ghosts->body[g].angular_velocity;
    if (!ghosts->body[g].sleeping) {
      world_->wake(bi);
      foreign_awake = true;
    }
  }
  // Sleeping bodies are not stepped at all; the statics count as asleep in the engine or not,
  // so compare the dynamic bodies' state directly.
  std::size_t awake = 0;
  for (std::size_t k = 0; k < bodies; ++k)
    awake += !world_->asleep(physics::BodyIndex(first_dynamic_ + k));
  if (awake == 0 && !foreign_awake) return 0;
  std::size_t frozen_before = world_->quarantined().size();
  world_->step(dt);
  quarantined_ += world_->quarantined().size() - frozen_before;
  awake = 0;
  for (std::size_t k = 0; k < bodies; ++k) {
    auto bi = physics::BodyIndex(first_dynamic_ + k);
    std::size_t i = *store.indexOf(body_entity_[k]);
    store.pos[i] = s.position[bi];
    store.vel[i] = s.linear_velocity[bi];
    store.rot[i] = s.orientation[bi];
    store.body[i].angular_velocity = s.angular_velocity[bi];
    store.body[i].sleeping = world_->asleep(bi);
    awake += !store.body[i].sleeping;
  }
  // What our bodies did to the foreign ones: their velocity change less gravity's (they have
  // no damping or other forces here). Round-off of that subtraction is far below 1e-9 m/s.
  const Vec3 gravity_dv = world_->forces().gravity * dt;
  for (std::size_t k = 0; k < foreign.size(); ++k) {
    std::size_t g = foreign[k];
    auto bi = physics::BodyIndex(first_foreign + k);
    if (world_->asleep(bi)) continue;
    GhostImpulse imp{ghosts->id[g], ghosts->owner[g],
                     s.linear_velocity[bi] - ghosts->vel[g] - gravity_dv,
                     s.angular_velocity[bi] - ghosts->body[g].angular_velocity};
    if (imp.dv.squaredNorm() + imp.dw.squaredNorm() > 1e-18) ghost_impulses_.push_back(imp);
  }
  return awake;
}

void RigidBodySystem::applyImpulses(EntityStore& store, const std::vector<GhostImpulse>& in) {
  for (const GhostImpulse& imp : in) {
    std::optional<std::size_t> i = store.indexOf(imp.id);
    if (!i) continue;  // cannot happen before migrate: the owner still holds its bodies
    store.vel[*i] += imp.dv;
    store.body[*i].angular_velocity += imp.dw;
    store.body[*i].sleeping = false;
    if (!world_) continue;
    auto k = std::find(body_entity_.begin(), body_entity_.end(), imp.id);
    if (k == body_entity_.end()) continue;
    auto bi = physics::BodyIndex(first_dynamic_ + (k - body_entity_.begin()));
    world_->bodies().linear_velocity[bi] = store.vel[*i];
    world_->bodies().angular_velocity[bi] = store.body[*i].angular_velocity;
    world_->wake(bi);
  }
}

}  // namespace zonesim::zone
