#pragma once
// Scene description of AI agents (docs/scene-format.md, `agents`): agent types, each composing a
// decision behaviour with perception, needs (health, energy) and locomotion, the populations that
// use them and the path service's budget (doors are cells of the map: scene_map.h). Plain data;
// zone_node/systems/agent_*.cpp give it life.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace zonesim {

/// What an agent senses each tick; machine files and trees name these inputs.
enum class AgentSense { EnemyDistance, Health, Energy, Arrived, Time, Count };
/// Input names as written in files, in AgentSense order.
inline constexpr const char* kAgentSenseNames[] = {"enemy_distance", "health", "energy", "arrived",
                                                   "time"};

/// What a decision asks the body to do this tick.
enum class AgentAction { Idle, Wander, Chase, Flee, Attack, Travel, Count };
/// Action names as written in scenes, in AgentAction order.
inline constexpr const char* kAgentActionNames[] = {"idle", "wander", "chase",
                                                    "flee", "attack", "travel"};

/// One node of a decision tree: a test `sense < threshold` (sense >= 0) or a leaf (sense < 0).
struct AgentTreeNode {
  int sense = -1;        ///< AgentSense index, -1 for a leaf
  double threshold = 0;  ///< test: true when the sense is below it
  int if_less = -1;      ///< test: node when true
  int otherwise = -1;    ///< test: node when false
  int action = 0;        ///< leaf: AgentAction index
};

/// One fuzzy state: active as a trapezoid of one sense; outputs blended by membership.
struct AgentFuzzyState {
  int sense = 0;                      ///< AgentSense index
  double a = 0, b = 0, c = 0, d = 0;  ///< trapezoid corners, a <= b <= c <= d
  double speed = 0;                   ///< m/s contributed
  double approach = 0;                ///< -1 (away from the enemy) .. 1 (toward it)
};

/// A GOAP action of a scene: pre/effects over the type's facts, done at a place for a time.
struct AgentGoapAction {
  std::string name;                 ///< for logs and tests
  std::uint64_t pre_mask = 0;       ///< facts constrained before
  std::uint64_t pre_values = 0;     ///< their required values
  std::uint64_t effect_mask = 0;    ///< facts set after
  std::uint64_t effect_values = 0;  ///< their new values
  double cost = 1;                  ///< > 0
  double x = 0, z = 0;              ///< where the action is done
  double duration_s = 0;            ///< time spent there
};

/// Goal-oriented planning of a type: facts, actions, the start state and the goal.
struct AgentGoap {
  std::vector<std::string> facts;        ///< at most 64
  std::vector<AgentGoapAction> actions;  ///< in file order
  std::uint64_t initial = 0;             ///< facts true at the start
  std::uint64_t goal_mask = 0;           ///< facts the goal constrains
  std::uint64_t goal_values = 0;         ///< their wanted values
};

/// An agent type: a decision behaviour composed with perception, needs and locomotion.
struct AgentType {
  /// How the type decides what to do.
  enum class Behaviour { Fsm, Guard, Tree, Fuzzy, Goap, Travel };
  std::string name;  ///< unique among the types
  std::string file;  ///< scene file (as named to the loader), for errors found later
  int line = 0;      ///< scene line of the type, for errors found when its files load
  Behaviour behaviour = Behaviour::Travel;
  std::string machine;  ///< fsm: machine file, resolved against the scene's folder
  std::vector<std::pair<std::string, int>> state_actions;  ///< fsm: leaf state -> AgentAction
  std::vector<AgentTreeNode> tree;                         ///< tree: nodes, root first
  std::vector<AgentFuzzyState> fuzzy;                      ///< fuzzy: states
  AgentGoap goap;                                          ///< goap: the domain
  double speed = 2.0;                                      ///< m/s top speed
  double acceleration = 4.0;                               ///< m/s^2
  double sight = 10.0;              ///< m: enemies farther are not seen (at most halo.width)
  double wander_radius = 20;        ///< m: wander waypoints are drawn within this distance
  double arrive_distance = 0.5;     ///< m: a goal counts as reached inside this distance
  double damage_range = 2.0;        ///< m: an enemy this close hurts
  double damage_per_s = 10;         ///< health lost per second while hurt
  double regen_per_s = 5;           ///< health regained per second otherwise (health is 0..100)
  double energy_drain_per_s = 0;    ///< energy lost per second at full speed
  double energy_recover_per_s = 0;  ///< energy regained per second while standing (0..100)
  std::vector<std::pair<double, double>> goals;  ///< travel: (x, z) visited in turn
  double dwell_s = 0;     ///< travel: seconds spent at a goal before the next
  bool navigate = false;  ///< travel and goap moves follow planned paths on the map
};

/// Agents of one type placed at random in a region.
struct AgentPopulation {
  int type = 0;  ///< index into AgentSettings::types
  int count = 0;
  double min_x = 0, min_z = 0, max_x = 0, max_z = 0;  ///< start region on the ground
};

/// Which planner serves a zone's navigating agents.
enum class AgentPlanner { AStar, Hpa, NavMesh, Jps };

/// The path service shared by a zone's navigating agents.
struct AgentPathSettings {
  /// `map.navigation` (grid, hpa, navmesh, jps), or its older spelling `agents.paths.planner`
  /// (astar, hpa, jps).
  AgentPlanner planner = AgentPlanner::AStar;
  int cluster_size = 16;        ///< HPA* cluster side, cells
  int paths_per_tick = 8;       ///< planner calls per tick and zone
  int expansions_per_tick = 0;  ///< node expansions per tick and zone (0: no limit)
  int cache = 1024;             ///< cached paths per zone (0: none; a hit equals a fresh plan)
  int landmarks = 0;  ///< landmark cells for the grid and jps planners (0: octile estimate)
  /// Measure each planned path against the A* optimum (ai::PathServiceConfig::audit): for
  /// tuning; costs a search per plan, changes no path.
  bool audit = false;
};

/// Everything under the scene's `agents` key.
struct AgentSettings {
  std::vector<AgentType> types;
  std::vector<AgentPopulation> populations;
  AgentPathSettings paths;
  /// Time-sliced decisions: each agent senses and decides on one tick in this many (which one
  /// from its id, so the agents spread evenly over the ticks) and acts on what it last
  /// perceived in between; it moves every tick. 1: every agent decides every tick.
  int decide_every = 1;
};

}  // namespace zonesim
