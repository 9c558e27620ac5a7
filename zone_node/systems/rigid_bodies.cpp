#include "zone_node/systems/rigid_bodies.h"

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

RigidBodySystem::RigidBodySystem(const Scene& scene) : scene_(scene) {}

RigidBodySystem::~RigidBodySystem() = default;

void RigidBodySystem::rebuild(const EntityStore& store) {
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
    const BodyData& b = store.body[i];
    physics::BodyDesc d;
    d.shape = shapeOf(b);
    d.position = store.pos[i];
    d.orientation = store.rot[i];
    d.linear_velocity = store.vel[i];
    d.angular_velocity = b.angular_velocity;
    d.density = b.mass / volumeOf(b);
    d.friction = b.friction;
    d.restitution = b.restitution;
    world_->addBody(d);
    body_entity_.push_back(store.id[i]);
    members_.add(store.id[i]);
  }
  ++rebuilds_;
}

std::size_t RigidBodySystem::step(EntityStore& store, double dt) {
  IdSetDigest now;
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.kind[i] == EntityKind::RigidBody) now.add(store.id[i]);
  if (now.count == 0) {
    world_.reset();
    members_ = {};
    return 0;
  }
  if (!world_ || !(now == members_)) rebuild(store);
  std::size_t bodies = body_entity_.size();
  // Sleeping bodies are not stepped at all; the statics count as asleep in the engine or not,
  // so compare the dynamic bodies' state directly.
  std::size_t awake = 0;
  for (std::size_t k = 0; k < bodies; ++k)
    awake += !world_->asleep(physics::BodyIndex(first_dynamic_ + k));
  if (awake == 0) return 0;
  std::size_t frozen_before = world_->quarantined().size();
  world_->step(dt);
  quarantined_ += world_->quarantined().size() - frozen_before;
  const physics::BodyStorage& s = world_->bodies();
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
  return awake;
}

}  // namespace zonesim::zone
