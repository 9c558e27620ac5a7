#include "zone_node/systems/ant_movement.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/scene.h"
#include "common/scene_source.h"
#include "common/splitmix.h"
#include "crowd/ant_trip_rule.h"
#include "zone_node/systems/crowd_lod.h"
#include "zone_node/systems/steering.h"
#include "zone_node/world_map.h"

namespace zonesim::zone {

namespace {

/// Uniform in [0, 1) from (seed, ant, tick, draw) alone: no ant's draws depend on which other
/// ants a rank holds, nor on the order it steps them.
double counterUniform(std::uint64_t seed, std::uint64_t id, std::uint64_t tick, int draw) {
  std::uint64_t z =
      splitmix64(splitmix64(splitmix64(seed) ^ id) ^ (tick * 4 + std::uint64_t(draw)));
  return double(z >> 11) * 0x1.0p-53;
}

}  // namespace

/// One colony: the scene's colony as crowd's trip rule and trail, and the figures of its ants.
struct AntMovement::Colony {
  Colony(std::int32_t p, const NpcColony& c, const WorldMap& m, ai::Cell nest, ai::Cell food,
         double dt)
      : population(p),
        cfg(c),
        map(m),
        trips(m.grid, nest, food,
              {{c.alpha, c.beta, c.knows_food, c.exploitation}, c.deposit, c.max_steps}),
        trail(m.grid, c.initial_pheromone, c.evaporation, dt) {}

  std::int32_t population;
  const NpcColony& cfg;
  const WorldMap& map;
  crowd::AntTripRule trips;
  crowd::AntTrail trail;
  std::size_t offset = 0;  // first cell of this colony in deltas_
  ColonyStats stats;
};

AntMovement::AntMovement(const Scene& scene, const WorldMap* map)
    : seed_(scene.seed), lod_(scene.lod.enabled), lod_settings_(lodOf(scene.lod)) {
  for (std::size_t p = 0; p < scene.npcs.size(); ++p) {
    const NpcColony& c = scene.npcs[p].colony;
    if (!c.enabled) continue;
    if (!map) throw SceneError(sceneFile(scene) + ":0: map: an ant colony needs a map");
    auto place = [&](const ScenePoint& at, const char* what) {
      if (!map->walkable(at.x, at.z)) {
        throw SceneError(sceneFile(scene) + ":" + std::to_string(at.line) + ": populations[" +
                         std::to_string(p) + "].colony." + what +
                         ": lies on a blocked cell of the map");
      }
      return map->frame.cellOf({at.x, at.z});
    };
    const ai::Cell nest = place(c.nest, "nest"), food = place(c.food, "food");
    if (nest == food) {
      throw SceneError(sceneFile(scene) + ":" + std::to_string(c.food.line) + ": populations[" +
                       std::to_string(p) + "].colony.food: lies in the nest's cell");
    }
    auto col = std::make_unique<Colony>(std::int32_t(p), c, *map, nest, food, scene.dt);
    col->offset = deltas_.size();
    deltas_.resize(deltas_.size() + col->trail.size(), 0);
    colonies_.push_back(std::move(col));
  }
}

AntMovement::~AntMovement() = default;

std::int32_t AntMovement::population(std::size_t c) const {
  return colonies_[c]->population;
}

const ColonyStats& AntMovement::stats(std::size_t c) const {
  return colonies_[c]->stats;
}

double AntMovement::trail(std::size_t c, ai::Cell cell) const {
  return colonies_[c]->trail.at(cell);
}

double AntMovement::totalTrail(std::size_t c) const {
  return colonies_[c]->trail.total();
}

std::vector<ai::Cell> AntMovement::trailRoute(std::size_t c) const {
  const Colony& col = *colonies_[c];
  return col.trail.strongestRoute(col.trips.nest(), col.trips.food());
}

void AntMovement::step(StepContext& ctx) {
  walk(ctx.store, ctx.tick, ctx.dt, ctx.players);
  if (ctx.cluster.sum) ctx.cluster.sum(deltas_);
  applyTrails();
}

void AntMovement::walk(EntityStore& store, std::uint64_t tick, double dt,
                       std::span<const crowd::Vec2> players) {
  std::fill(deltas_.begin(), deltas_.end(), 0);
  updates_ = 0;
  const double time = double(tick) * dt;
  for (const std::unique_ptr<Colony>& cp : colonies_) {
    Colony& col = *cp;
    const crowd::MapFrame& frame = col.map.frame;
    const bool food_there = col.cfg.food_until < 0 || time < col.cfg.food_until;
    for (std::size_t i = 0; i < store.size(); ++i) {
      if (store.kind[i] != EntityKind::Npc || store.npc[i].population != col.population) continue;
      AntData& ant = crowdState<AntData>(store.npc[i]);
      const std::uint64_t id = store.id[i].value;
      const crowd::Vec2 from{store.pos[i].x(), store.pos[i].z()};
      // Level of detail: an ant of period k walks on one tick in k, standing for the k ticks.
      int period = 1;
      if (lod_) {
        period = crowd::lodPeriod(crowd::lodLevel(from, players, lod_settings_), lod_settings_);
        if (!crowd::lodDue(id, std::int64_t(tick), period)) continue;
      }
      ++updates_;
      col.trips.begin(ant);
      // The walk of the `period` ticks this update stands for, as full detail takes it: speed
      // * dt a tick, stopping at a cell centre on the tick it gets there and deciding on it,
      // with that tick's draws. Only the trail it reads is older. A period of 1 is exactly the
      // full-detail walk.
      const double reach = col.cfg.speed * dt;
      int ticks_left = period;
      crowd::Vec2 at = from;
      while (ticks_left > 0) {
        const crowd::Vec2 to = frame.centre(col.trips.target(ant)) - at;
        const double d = crowd::length(to);
        if (d > reach * ticks_left) {
          at = at + to * (reach * ticks_left / d);
          break;
        }
        at = at + to;
        // At a cell centre: the ant decides where to go next (at most once per tick), on the
        // tick it got there.
        const int ticks = std::clamp(int(std::ceil(d / reach)), 1, ticks_left);
        const std::uint64_t as_of = tick + 1 - std::uint64_t(ticks_left) + std::uint64_t(ticks - 1);
        ticks_left -= ticks;
        const crowd::AntArrival arrival =
            col.trips.arrive(ant, col.trail, food_there,
                             [&](int draw) { return counterUniform(seed_, id, as_of, draw); });
        deltas_[col.offset + col.trail.index(arrival.cell)] += arrival.laid;
        if (arrival.trip_length > 0) {
          ++col.stats.trips;
          col.stats.length_sum += arrival.trip_length;
          col.stats.last_length = arrival.trip_length;
        }
      }
      const double moved_dt = dt * period;
      store.pos[i] = Vec3(at.x, store.pos[i].y(), at.y);
      store.vel[i] = Vec3((at.x - from.x) / moved_dt, 0.0, (at.y - from.y) / moved_dt);
      store.rot[i] = facing(store.rot[i], store.vel[i]);
    }
  }
}

void AntMovement::applyTrails() {
  for (const std::unique_ptr<Colony>& cp : colonies_) {
    Colony& col = *cp;
    col.trail.evaporateAndAdd(
        std::span<const std::int64_t>(deltas_).subspan(col.offset, col.trail.size()));
  }
}

}  // namespace zonesim::zone
