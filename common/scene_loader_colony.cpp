// The `colony` block of an NPC population (docs/scene-format.md): ants exploring the scene's
// map from a nest toward food, with pheromone trails that evaporate.

#include "common/scene.h"
#include "common/scene_loader_crowd.h"

namespace zonesim {

void readNpcColony(const SceneMap& population, const Scene& scene, NpcPopulation& p) {
  if (!population.optional("colony")) return;
  for (const char* other : {"separation", "gather", "flock", "flow", "formation"}) {
    if (population.optional(other))
      population.failAt(other, "an ant colony walks its trails, not this");
  }
  NpcColony& c = p.colony;
  c.enabled = true;
  SceneMap m = population.section(
      "colony", {"nest", "food", "food_until", "alpha", "beta", "knows_food", "evaporation",
                 "deposit", "exploitation", "initial_pheromone", "speed", "max_steps"});
  if (!scene.map.present()) m.failAt("nest", "an ant colony needs the scene's map: key");
  c.nest = readGroundPoint(m.required("nest"), scene);
  c.food = readGroundPoint(m.required("food"), scene);
  m.read("food_until", c.food_until, Limit::atLeast(0));
  m.read("alpha", c.alpha, Limit::between(0, 10));
  m.read("beta", c.beta, Limit::between(0, 10));
  m.read("knows_food", c.knows_food);
  m.read("evaporation", c.evaporation, Limit::between(0, 1));
  m.read("deposit", c.deposit, Limit::above(0));
  m.read("exploitation", c.exploitation, Limit::between(0, 1));
  m.read("initial_pheromone", c.initial_pheromone, Limit::above(0));
  m.read("speed", c.speed, Limit::above(0));
  m.read("max_steps", c.max_steps, Limit::atLeast(0));
  // Trails are fixed-point integers (zone_node/systems/ant_movement.h): keep the deposit and
  // the floor well inside their range.
  if (c.deposit > 1e6) m.failAt("deposit", "at most 1e6");
  if (c.initial_pheromone > 1e6) m.failAt("initial_pheromone", "at most 1e6");
}

}  // namespace zonesim
