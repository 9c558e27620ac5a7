#include "zone_node/population.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>

#include "common/rng.h"
#include "common/scene.h"
#include "common/scene_source.h"
#include "zone_node/formation_start.h"
#include "zone_node/systems/scene_shapes.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {

namespace {

Vec3 uniformIn(Pcg32& rng, const SceneBox& box, double y) {
  return Vec3(rng.uniform(box.min.x, box.max.x), y, rng.uniform(box.min.z, box.max.z));
}

/// Each entity's generator: stream from its id, so draws never depend on which rank runs it.
Pcg32 entityRng(const Scene& scene, EntityId id) {
  return Pcg32(scene.seed, id.value);
}

/// The next scene entity of a kind: its id (the global index) and its own random stream.
std::pair<EntityRecordData, Pcg32> nextSceneEntity(const Scene& scene, EntityKind kind,
                                                   std::uint64_t& counter) {
  EntityRecordData r;
  r.id = EntityId::make(kSceneCreator, ++counter);
  r.kind = kind;
  return {r, entityRng(scene, r.id)};
}

}  // namespace

Vec3 nextWaypoint(const Scene& scene, const Vec3& from, double radius, std::uint64_t& rng_state,
                  EntityId id) {
  Pcg32 rng = Pcg32::fromState(rng_state, id.value);
  double angle = rng.uniform(0.0, 2.0 * M_PI);
  double dist = radius * std::sqrt(rng.uniform());
  rng_state = rng.state();
  const double margin = 0.5;
  return Vec3(std::clamp(from.x() + dist * std::cos(angle), scene.world.min.x + margin,
                         scene.world.max.x - margin),
              scene.world.min.y,
              std::clamp(from.z() + dist * std::sin(angle), scene.world.min.z + margin,
                         scene.world.max.z - margin));
}

namespace {

// With a map, NPCs start on open cells: draws in the region are repeated (from the NPC's own
// stream, so every rank draws the same) until one lands on an open cell.
Vec3 openStart(Pcg32& rng, const NpcPopulation& p, const Scene& scene, const WorldMap* map,
               std::size_t group) {
  constexpr int kTries = 10000;
  for (int t = 0; t < kTries; ++t) {
    Vec3 at = uniformIn(rng, p.region, scene.world.min.y);
    if (!map || map->walkable(at.x(), at.z())) return at;
  }
  throw SceneError(sceneFile(scene) + ":0: populations[" + std::to_string(group) +
                   "].region: " + std::to_string(kTries) + " draws found no open cell of the map");
}

}  // namespace

bool wanders(const NpcPopulation& p) {
  return !(p.flock.enabled || p.flow.enabled || p.colony.enabled || p.roads.enabled ||
           p.formation.enabled);
}

void forEachInitialEntity(const Scene& scene,
                          const std::function<void(const EntityRecordData&)>& keep) {
  std::shared_ptr<const WorldMap> map = loadWorldMap(scene);
  std::uint64_t counter = 0;
  for (std::size_t group = 0; group < scene.npcs.size(); ++group) {
    const NpcPopulation& p = scene.npcs[group];
    for (int i = 0; i < p.count; ++i) {
      auto [r, rng] = nextSceneEntity(scene, EntityKind::Npc, counter);
      r.pos = openStart(rng, p, scene, map.get(), group);
      r.npc.max_speed = rng.uniform(p.min_speed, p.max_speed);
      r.npc.accel = p.acceleration;
      r.npc.waypoint_radius = p.waypoint_radius;
      r.npc.arrive_distance = p.arrive_distance;
      r.npc.separation_radius = p.separation_radius;
      r.npc.separation_weight = p.separation_weight;
      r.npc.gather_point = Vec3(p.gather.x, scene.world.min.y, p.gather.z);
      r.npc.gather_radius = p.gather.radius;
      r.npc.gather_start = p.gather.start_s;
      r.npc.gather_end = p.gather.end_s;
      r.rng_state = rng.state();
      r.npc.waypoint = nextWaypoint(scene, r.pos, p.waypoint_radius, r.rng_state, r.id);
      if (p.flock.enabled) {
        // A flock starts with random headings at flocking speed; alignment orders it.
        r.npc.population = std::int32_t(group);
        Pcg32 more = Pcg32::fromState(r.rng_state, r.id.value);
        double heading = more.uniform(0.0, 2.0 * M_PI);
        double speed = std::min(r.npc.max_speed, p.flock.max_speed);
        r.vel = Vec3(speed * std::cos(heading), 0, speed * std::sin(heading));
        r.rng_state = more.state();
      }
      // A flow NPC starts at rest; the flow system moves it (the population index tells it
      // apart from wanderers, as for flocks).
      if (p.flow.enabled) r.npc.population = std::int32_t(group);
      // An ant starts at rest in its nest's cell centre, its route that one cell.
      if (p.colony.enabled) {
        r.npc.population = std::int32_t(group);
        ai::Cell nest = map->frame.cellOf({p.colony.nest.x, p.colony.nest.z});
        crowd::Vec2 at = map->frame.centre(nest);
        r.pos = Vec3(at.x, scene.world.min.y, at.y);
        crowdState<AntData>(r.npc).route = {nest.x, nest.y};
      }
      // A road NPC starts at rest on a node drawn from its stream, which is its first goal.
      if (p.roads.enabled) {
        r.npc.population = std::int32_t(group);
        Pcg32 more = Pcg32::fromState(r.rng_state, r.id.value);
        const int start = int(more.next() % std::uint32_t(p.roads.nodes.size()));
        r.pos = Vec3(p.roads.nodes[std::size_t(start)].x, scene.world.min.y,
                     p.roads.nodes[std::size_t(start)].z);
        r.npc.crowd = RoadTripData{start, start};
        r.rng_state = more.state();
      }
      // A formation member starts at rest at its slot (its index in the population).
      if (p.formation.enabled) {
        r.npc.population = std::int32_t(group);
        r.npc.crowd = FormationMemberData{};
        crowd::Vec2 at = formationStart(scene, *map, group, i);
        r.pos = Vec3(at.x, scene.world.min.y, at.y);
      }
      keep(r);
    }
  }
  for (const RigidBodyPopulation& p : scene.rigid_bodies) {
    for (int i = 0; i < p.count; ++i) {
      auto [r, rng] = nextSceneEntity(scene, EntityKind::RigidBody, counter);
      double lift = boundingRadius(p) + rng.uniform(p.drop_height, p.max_drop_height);
      r.pos = uniformIn(rng, p.region, scene.world.min.y + lift);
      r.vel = Vec3(rng.uniform(-2, 2), 0, rng.uniform(-2, 2));
      r.body.angular_velocity = Vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
      r.body.shape = std::uint8_t(p.shape);
      r.body.radius = p.radius;
      r.body.half_extents = Vec3(p.size.x, p.size.y, p.size.z) * 0.5;
      r.body.half_height = 0.5 * p.length;
      r.body.mass = p.mass;
      r.body.friction = p.friction;
      r.body.rolling_resistance = p.rolling_resistance;
      r.body.restitution = p.restitution;
      r.body.linear_damping = p.linear_damping;
      r.body.angular_damping = p.angular_damping;
      r.rng_state = rng.state();
      keep(r);
    }
  }
  for (const EmitterPopulation& p : scene.emitters) {
    for (int i = 0; i < p.count; ++i) {
      auto [r, rng] = nextSceneEntity(scene, EntityKind::Emitter, counter);
      r.pos = uniformIn(rng, p.region, scene.world.min.y);
      r.emitter.rate = p.rate;
      r.emitter.lifetime = p.lifetime;
      r.emitter.speed = p.speed;
      r.emitter.drag = p.drag;
      r.emitter.restitution = p.restitution;
      r.emitter.max_particles = p.max_particles;
      r.rng_state = rng.state();
      keep(r);
    }
  }
  // Named bodies come last, so adding them leaves every other entity's id as it was. Static
  // and kinematic ones are scene geometry, not entities, but keep their ids reserved so that
  // namedBodyId() holds for every body.
  for (const SceneBody& b : scene.physics.bodies) {
    auto [r, rng] = nextSceneEntity(scene, EntityKind::RigidBody, counter);
    if (b.motion != SceneBody::Motion::Dynamic) continue;
    r.pos = entityStart(b);
    r.rot = toQuat(b.orientation);
    r.vel = toVec3(b.velocity);
    r.body.angular_velocity = toVec3(b.angular_velocity);
    r.body.shape = std::uint8_t(b.shape);
    r.body.radius = b.radius;
    r.body.half_extents = Vec3(b.size.x, b.size.y, b.size.z) * 0.5;
    r.body.half_height = 0.5 * b.length;
    r.body.mass = b.mass;
    r.body.friction = b.friction;
    r.body.rolling_resistance = b.rolling_resistance;
    r.body.restitution = b.restitution;
    r.body.linear_damping = b.linear_damping;
    r.body.angular_damping = b.angular_damping;
    r.rng_state = rng.state();
    keep(r);
  }
  // AI agents after everything else (named bodies included), so scenes without them keep every
  // other entity's id. On a map they start on open ground: positions on blocked cells are drawn
  // again (from the agent's own stream).
  for (const AgentPopulation& p : scene.agents.populations) {
    const AgentType& type = scene.agents.types[std::size_t(p.type)];
    for (int i = 0; i < p.count; ++i) {
      auto [r, rng] = nextSceneEntity(scene, EntityKind::Npc, counter);
      for (int draw = 0; draw < 1000; ++draw) {
        r.pos =
            Vec3(rng.uniform(p.min_x, p.max_x), scene.world.min.y, rng.uniform(p.min_z, p.max_z));
        if (!map || map->walkable(r.pos.x(), r.pos.z())) break;
      }
      r.npc.max_speed = type.speed;
      r.npc.accel = type.acceleration;
      r.npc.waypoint_radius = type.wander_radius;
      r.npc.arrive_distance = type.arrive_distance;
      r.agent.type = p.type;
      r.agent.facts = type.goap.initial;
      // Travellers start at a goal of their own, so they spread over the routes.
      if (!type.goals.empty()) r.agent.goal = std::int32_t(rng.next() % type.goals.size());
      r.rng_state = rng.state();
      r.npc.waypoint = nextWaypoint(scene, r.pos, type.wander_radius, r.rng_state, r.id);
      keep(r);
    }
  }
  // Items after them: a scene that gains items keeps every other entity's id.
  for (const auto& at : scene.interactions.items) {
    auto [r, rng] = nextSceneEntity(scene, EntityKind::Item, counter);
    r.pos = Vec3(at[0], scene.world.min.y, at[1]);
    keep(r);
  }
}

EntityId namedBodyId(const Scene& scene, std::size_t k) {
  std::uint64_t before = 0;
  for (const NpcPopulation& p : scene.npcs) before += std::uint64_t(p.count);
  for (const RigidBodyPopulation& p : scene.rigid_bodies) before += std::uint64_t(p.count);
  for (const EmitterPopulation& p : scene.emitters) before += std::uint64_t(p.count);
  return EntityId::make(kSceneCreator, before + k + 1);
}

}  // namespace zonesim::zone
