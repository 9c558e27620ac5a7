#include "zone_node/systems/ant_movement.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/scene.h"
#include "common/scene_source.h"
#include "common/splitmix.h"
#include "crowd/ant_step.h"
#include "crowd/grid_step.h"
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

bool contains(const std::vector<std::int32_t>& cells, ai::Cell c) {
  for (std::size_t k = 0; k + 1 < cells.size(); k += 2)
    if (cells[k] == c.x && cells[k + 1] == c.y) return true;
  return false;
}

ai::Cell cellAt(const std::vector<std::int32_t>& cells, std::int32_t k) {
  return {cells[std::size_t(2 * k)], cells[std::size_t(2 * k + 1)]};
}

std::int32_t cellCount(const std::vector<std::int32_t>& cells) {
  return std::int32_t(cells.size() / 2);
}

}  // namespace

/// One colony: where its nest and food are, its trail grid and the figures of its ants.
struct AntMovement::Colony {
  Colony(std::int32_t p, const NpcColony& c, const WorldMap& m)
      : population(p), cfg(c), map(m), choice{c.alpha, c.beta, c.knows_food, c.exploitation} {}

  std::size_t index(ai::Cell c) const { return std::size_t(map.grid.index(c.x, c.y)); }
  bool adjacent(ai::Cell a, ai::Cell b) const {
    for (int k = 0; k < 8; ++k)
      if (crowd::gridStep(a, k) == b) return crowd::gridStepAllowed(map.grid, a, k);
    return false;
  }
  /// Replaces `route` (x, y pairs, nest first) by the route home from its last cell that
  /// always steps to the earliest route cell next to the current one.
  void shorten(std::vector<std::int32_t>& route) const {
    std::vector<std::int32_t> back;
    std::int32_t at = cellCount(route) - 1;
    back.insert(back.end(), {route[std::size_t(2 * at)], route[std::size_t(2 * at + 1)]});
    while (at > 0) {
      std::int32_t j = 0;
      while (j < at - 1 && !adjacent(cellAt(route, at), cellAt(route, j))) ++j;
      at = j;
      back.insert(back.end(), {route[std::size_t(2 * at)], route[std::size_t(2 * at + 1)]});
    }
    route.clear();
    for (std::size_t k = back.size(); k >= 2; k -= 2)
      route.insert(route.end(), {back[k - 2], back[k - 1]});
  }

  std::int32_t population;
  const NpcColony& cfg;
  const WorldMap& map;
  crowd::AntChoice choice;
  ai::Cell nest, food;
  std::size_t offset = 0;           // first cell of this colony in deltas_
  std::vector<std::int64_t> trail;  // fixed point, kTrailScale per unit
  std::uint64_t keep = 0;           // fraction kept per tick, 32.32 fixed point
  int max_steps = 0;
  ColonyStats stats;
};

AntMovement::AntMovement(const Scene& scene, const WorldMap* map) : seed_(scene.seed) {
  for (std::size_t p = 0; p < scene.npcs.size(); ++p) {
    const NpcColony& c = scene.npcs[p].colony;
    if (!c.enabled) continue;
    if (!map) throw SceneError(sceneFile(scene) + ":0: map: an ant colony needs a map");
    auto col = std::make_unique<Colony>(std::int32_t(p), c, *map);
    auto place = [&](const ScenePoint& at, const char* what) {
      if (!map->walkable(at.x, at.z)) {
        throw SceneError(sceneFile(scene) + ":" + std::to_string(at.line) + ": populations[" +
                         std::to_string(p) + "].colony." + what +
                         ": lies on a blocked cell of the map");
      }
      return map->frame.cellOf({at.x, at.z});
    };
    col->nest = place(c.nest, "nest");
    col->food = place(c.food, "food");
    if (col->nest == col->food) {
      throw SceneError(sceneFile(scene) + ":" + std::to_string(c.food.line) + ": populations[" +
                       std::to_string(p) + "].colony.food: lies in the nest's cell");
    }
    const std::size_t cells = std::size_t(map->grid.width()) * std::size_t(map->grid.height());
    col->offset = deltas_.size();
    deltas_.resize(deltas_.size() + cells, 0);
    col->trail.assign(cells,
                      std::max<std::int64_t>(1, std::llround(c.initial_pheromone * kTrailScale)));
    // The same double on every rank, rounded once: evaporation is then integer arithmetic.
    col->keep = std::uint64_t(std::llround(std::pow(1.0 - c.evaporation, scene.dt) * 0x1.0p32));
    col->max_steps = c.max_steps > 0 ? c.max_steps : 4 * map->grid.passableCount();
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
  const Colony& col = *colonies_[c];
  return double(col.trail[col.index(cell)]) / kTrailScale;
}

double AntMovement::totalTrail(std::size_t c) const {
  std::int64_t sum = 0;
  for (std::int64_t t : colonies_[c]->trail) sum += t;
  return double(sum) / kTrailScale;
}

std::vector<ai::Cell> AntMovement::trailRoute(std::size_t c) const {
  const Colony& col = *colonies_[c];
  std::vector<ai::Cell> out;
  auto strength = [&](ai::Cell, int, ai::Cell n) { return col.trail[col.index(n)]; };
  if (!crowd::strongestTrailRoute(col.map.grid, col.nest, col.food, strength, out)) return {};
  return out;
}

void AntMovement::step(StepContext& ctx) {
  walk(ctx.store, ctx.tick, ctx.dt);
  if (ctx.cluster.sum) ctx.cluster.sum(deltas_);
  applyTrails();
}

void AntMovement::walk(EntityStore& store, std::uint64_t tick, double dt) {
  std::fill(deltas_.begin(), deltas_.end(), 0);
  const double time = double(tick) * dt;
  for (const std::unique_ptr<Colony>& cp : colonies_) {
    Colony& col = *cp;
    const crowd::MapFrame& frame = col.map.frame;
    const bool food_there = col.cfg.food_until < 0 || time < col.cfg.food_until;
    for (std::size_t i = 0; i < store.size(); ++i) {
      if (store.kind[i] != EntityKind::Npc || store.npc[i].population != col.population) continue;
      AntData& ant = crowdState<AntData>(store.npc[i]);
      const std::uint64_t id = store.id[i].value;
      if (ant.route.empty()) ant.route = {col.nest.x, col.nest.y};
      auto target = [&] {
        return ant.mode == std::int32_t(AntMode::Returning)
                   ? cellAt(ant.route, ant.route_at)
                   : cellAt(ant.route, cellCount(ant.route) - 1);
      };
      const crowd::Vec2 from{store.pos[i].x(), store.pos[i].z()};
      crowd::Vec2 to = frame.centre(target()) - from;
      const double reach = col.cfg.speed * dt, d = crowd::length(to);
      crowd::Vec2 at = from;
      if (d > reach) {
        at = from + to * (reach / d);
      } else {
        at = from + to;
        // At a cell centre: the ant decides where to go next (at most once per tick).
        ai::Cell c = target();
        if (ant.mode == std::int32_t(AntMode::Returning)) {
          if (ant.route_length > 0) {
            deltas_[col.offset + col.index(c)] += std::max<std::int64_t>(
                1, std::llround(col.cfg.deposit / ant.route_length * kTrailScale));
          }
          if (ant.route_at > 0) {
            --ant.route_at;
          } else {  // home: count the trip, start a new one
            if (ant.route_length > 0) {
              ++col.stats.trips;
              col.stats.length_sum += ant.route_length;
              col.stats.last_length = ant.route_length;
            }
            ant.mode = std::int32_t(AntMode::Searching);
            ant.route.assign({col.nest.x, col.nest.y});
            ant.dead_ends.clear();
            ant.route_length = 0;
            ant.route_at = 0;
          }
        } else if ((c == col.food && food_there) || cellCount(ant.route) > col.max_steps) {
          // Found it (lay trail all the way home), or gave up (walk home laying nothing). The
          // way home cuts the detours of the way out: from each cell it steps to the earliest
          // cell of its route that lies next to it (it remembers the route and senses its
          // neighbours), so it lays trail on a shorter route than it walked.
          col.shorten(ant.route);
          double length = 0;
          for (std::int32_t k = 1; k < cellCount(ant.route); ++k)
            length += ai::octileDistance(cellAt(ant.route, k - 1), cellAt(ant.route, k));
          const bool found = c == col.food && food_there;
          ant.mode = std::int32_t(AntMode::Returning);
          ant.route_length = found ? length : 0;
          ant.route_at = std::max(0, cellCount(ant.route) - 2);
          if (found) {
            deltas_[col.offset + col.index(c)] +=
                std::max<std::int64_t>(1, std::llround(col.cfg.deposit / length * kTrailScale));
          }
        } else {
          // Sense the eight cells around; weigh the open ones not yet walked on this trip.
          const int chosen = crowd::chooseAntStep(
              col.map.grid, c, col.food, col.choice,
              [&](int, ai::Cell n) { return double(col.trail[col.index(n)]) / kTrailScale; },
              [&](ai::Cell n) { return !contains(ant.route, n) && !contains(ant.dead_ends, n); },
              [&](int draw) { return counterUniform(seed_, id, tick, draw); });
          if (chosen < 0) {
            // Dead end: remember it and back off one cell (at the nest: start afresh).
            if (cellCount(ant.route) > 1) {
              ant.dead_ends.push_back(c.x);
              ant.dead_ends.push_back(c.y);
              ant.route.resize(ant.route.size() - 2);
            } else {
              ant.dead_ends.clear();
            }
          } else {
            const ai::Cell n = crowd::gridStep(c, chosen);
            ant.route.push_back(n.x);
            ant.route.push_back(n.y);
          }
        }
      }
      store.pos[i] = Vec3(at.x, store.pos[i].y(), at.y);
      store.vel[i] = Vec3((at.x - from.x) / dt, 0.0, (at.y - from.y) / dt);
      store.rot[i] = facing(store.rot[i], store.vel[i]);
    }
  }
}

void AntMovement::applyTrails() {
  for (const std::unique_ptr<Colony>& cp : colonies_) {
    Colony& col = *cp;
    const std::int64_t* delta = deltas_.data() + col.offset;
    for (std::size_t k = 0; k < col.trail.size(); ++k) {
      auto kept = std::int64_t((unsigned __int128)std::uint64_t(col.trail[k]) * col.keep >> 32);
      col.trail[k] = std::max<std::int64_t>(1, kept) + delta[k];
    }
  }
}

}  // namespace zonesim::zone
