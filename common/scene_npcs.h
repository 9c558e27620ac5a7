#pragma once
// NPC populations of a scene (`populations:` entries of kind npc, docs/scene-format.md): the
// wanderers' settings and the blocks that make a population a flock, a flow-field crowd, a
// formation, an ant colony or travellers of a road network.

#include <cstdint>
#include <string>
#include <vector>

#include "common/scene_geometry.h"

namespace zonesim {

/// Reynolds flocking for an NPC population (crowd/flock.h, docs/crowd.md).
struct NpcFlock {
  bool enabled = false;            ///< the population flocks instead of wandering
  double radius = 3.0;             ///< m: alignment and cohesion see neighbours this close
  double separation_radius = 1.0;  ///< m: pushed apart closer than this
  double separation_weight = 20;   ///< 1/s^2 per unit of (radius / distance - 1)
  double alignment_weight = 1.0;   ///< 1/s: velocity follows the neighbours' mean velocity
  double cohesion_weight = 0.5;    ///< 1/s^2: pull toward the neighbours' centre
  double max_speed = 2.0;          ///< m/s
  double max_force = 8.0;          ///< m/s^2, bound on the steering acceleration
  /// `goal`: a point the flock heads for; each flocker's goal velocity points at it at
  /// `goal_speed`, ramping down within `goal_slow_radius`, followed at `goal_weight`.
  bool has_goal = false;
  double goal_x = 0, goal_z = 0;  ///< the point on the ground plane
  double goal_weight = 1.0;       ///< 1/s: rate at which velocity follows the goal velocity
  double goal_speed = 0;          ///< m/s toward the point (the loader sets max_speed if unset)
  double goal_slow_radius = 5.0;  ///< m: the goal speed ramps down to 0 this close
  double body_radius = 0.0;       ///< m: bodies that never step into each other (0: may overlap)
};

/// A flow-field crowd (crowd/flow_crowd.h, docs/crowd.md): each NPC heads for one
/// of a few destinations on the scene's map, along a field computed once per destination.
struct NpcFlow {
  bool enabled = false;  ///< the population follows flow fields instead of wandering
  /// A goal on the ground plane; `line` is where the scene gives it (for errors on loading).
  struct Destination {
    double x = 0, z = 0;
    int line = 0;
  };
  std::vector<Destination> destinations;  ///< each NPC draws one from its id
  double max_speed = 2.0;                 ///< m/s
  double max_force = 10.0;                ///< m/s^2, bound on the steering acceleration
  double steer_rate = 4.0;                ///< 1/s: rate at which velocity follows the field
  double separation_radius = 0.6;         ///< m: pushed apart closer than this
  double separation_weight = 10.0;        ///< 1/s^2 per unit of (radius / distance - 1)
  double arrive_radius = 0.75;            ///< m from the goal cell's centre: arrived, stops
  double slow_radius = 2.0;               ///< m: speed ramps down this close to the goal
  double body_radius = 0.0;  ///< m: bodies that never step into each other (0: may overlap)
};

/// A road network: NPCs travel between waypoints of a weighted graph along cheapest paths
/// (ai/waypoint_graph.h, zone_node/systems/road_movement.h).
struct NpcRoads {
  bool enabled = false;  ///< the population travels the graph instead of wandering
  struct Edge {
    int a = 0, b = 0;         ///< node indices
    double cost = 0;          ///< > 0; the straight length unless the scene gives one
    std::uint32_t flags = 0;  ///< bits of flag_names the edge needs (door, ladder...)
    bool one_way = false;     ///< a -> b only
  };
  /// An edge shut from `from` until `until` (simulated seconds).
  struct Closure {
    int edge = 0;
    double from = 0, until = 0;
  };
  std::vector<ScenePoint> nodes;
  std::vector<Edge> edges;
  std::vector<std::string> flag_names;  ///< bit i of a flag set is flag_names[i]
  std::uint32_t may_use = 0;            ///< flags these NPCs may pass
  std::vector<Closure> closures;
};

/// A fixed group (crowd/formation.h, docs/crowd.md): the population's NPCs hold
/// slots around a centre that walks a route on the scene's map; a member cut off from the
/// group plans A* back to it and rejoins (`populations[].formation`).
struct NpcFormation {
  bool enabled = false;             ///< the population is a formation instead of wanderers
  std::vector<ScenePoint> route;    ///< the centre starts at the first; A* between points
  int columns = 4;                  ///< slots per row across the heading; rows trail behind
  double spacing = 1.5;             ///< m between neighbouring slots
  double centre_speed = 1.5;        ///< m/s of the centre along its route
  double max_speed = 2.5;           ///< m/s of a member (above the centre's, to catch up)
  double max_force = 8.0;           ///< m/s^2, bound on a member's steering acceleration
  double steer_rate = 4.0;          ///< 1/s: rate at which velocity follows the desired one
  double slot_gain = 2.0;           ///< 1/s: desired velocity per metre of slot error
  double slow_radius = 3.0;         ///< m: the centre slows down this close to its last point
  double turn_rate = 3.0;           ///< 1/s: rate at which the heading follows the route
  double cut_off = 5.0;             ///< m from its slot: a member is cut off
  double rejoin = 1.0;              ///< m from a visible slot: a rejoining member rejoins
  double replan = 2.0;              ///< m the centre moves before a rejoin path is re-planned
  double separation_radius = 0.6;   ///< m: members closer than this push apart
  double separation_weight = 10.0;  ///< 1/s^2 per unit of (radius / distance - 1)
};

/// An ant colony (docs/crowd.md): the population's NPCs are ants walking the scene's map cell
/// by cell from a nest, sensing only the cells next to them, laying pheromone on their way back
/// from the food; trails evaporate (`populations[].colony`).
struct NpcColony {
  bool enabled = false;             ///< the population is an ant colony
  ScenePoint nest, food;            ///< where the ants start and what they look for
  double food_until = -1;           ///< s of simulated time the food is taken away (<0: never)
  double alpha = 1.0;               ///< weight of the pheromone in a step's choice
  double beta = 2.0;                ///< weight of the heuristic desirability of a step
  bool knows_food = true;           ///< eta uses the straight-line distance to the food
  double evaporation = 0.05;        ///< fraction of every trail lost per second
  double deposit = 1.0;             ///< Q: a returning ant lays Q / (route length) per cell
  double exploitation = 0.0;        ///< q0: chance of taking the strongest step outright
  double initial_pheromone = 0.01;  ///< trail on every cell at the start
  double speed = 2.0;               ///< m/s of an ant
  int max_steps = 0;                ///< cells before a searching ant gives up (0: 4 x open cells)
};

/// Walking NPCs wandering between random waypoints, or flocking (`flock`).
struct NpcPopulation {
  int count = 0;
  double min_speed = 1.0;  ///< m/s, each NPC draws its top speed in [min, max]
  double max_speed = 2.0;
  double acceleration = 2.0;     ///< m/s^2 toward the waypoint
  double waypoint_radius = 30;   ///< next waypoint drawn within this distance
  double arrive_distance = 1.0;  ///< waypoint counts as reached inside this distance
  SceneBox region;               ///< where they start (defaults to the world)
  double separation_radius = 0;  ///< keep this far from other walkers (0: no avoidance)
  double separation_weight = 1;  ///< push at contact, in top speeds
  /// A gathering: from start_s to end_s of simulated time every NPC of the population heads for
  /// waypoints within `radius` of `point` (x, z); before and after, it wanders (a crowd that
  /// converges, then disperses). radius 0: no gathering.
  struct Gather {
    double x = 0, z = 0, radius = 0, start_s = 0, end_s = 0;
  } gather;
  NpcFlock flock;          ///< flocking instead of waypoints when enabled
  NpcFlow flow;            ///< flow-field crowd instead of waypoints when enabled
  NpcFormation formation;  ///< a fixed group instead of waypoints when enabled
  NpcColony colony;        ///< an ant colony instead of waypoints when enabled
  NpcRoads roads;          ///< travels a road network instead of wandering when enabled
};

}  // namespace zonesim
