#pragma once
// Ant colony optimisation for finding a route through terrain the ants do not know: each ant
// walks from the nest sensing only the cells next to it (walls are discovered by bumping into
// them), never revisiting a cell (a dead end makes it back off one step), and picks its next
// step with probability proportional to pheromone^alpha * eta^beta, or, with probability
// `exploitation`, the best such step outright (the ACS rule: exploitation against
// exploration). eta may use where the food is (as the crow flies; the terrain in between
// stays unknown) or nothing at all. Ants that find the food lay
// Q / length on the steps of their route; every iteration all trails evaporate by a fraction
// rho, so routes that stop being used fade and early detours do not pin the colony.
//
// The zone's ant colonies (zone_node/systems/ant_movement.h) are ants of the same rule stepped
// differently: entities that walk tick by tick, with a fixed-point trail per cell
// (crowd/ant_trail.h) that must end bitwise equal on any number of ranks, and a way home
// (crowd/ant_trip_rule.h). This colony is the textbook iteration-based ACS for studies: whole
// walks per iteration, one random stream, a double trail per directed step, an ant that is
// lost at a dead-ended nest or after max_steps moves (back-offs included), and no walk home.
// What the two share is written once: the step choice (crowd/ant_step.h) and the searching
// ant's decision with its dead-end back-off (AntTripRule::decide).

#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "common/rng.h"
#include "crowd/ant_step.h"
#include "crowd/ant_trip.h"
#include "crowd/ant_trip_rule.h"

namespace zonesim::crowd {

/// Colony parameters.
struct AntColonySettings {
  int ants = 20;                    ///< ants sent per iteration
  double alpha = 1.0;               ///< weight of pheromone in the step choice
  double beta = 2.0;                ///< weight of the heuristic desirability eta of a step
  bool knows_food_position = true;  ///< eta = 1 / (step + octile distance to the food); else
                                    ///< eta = 1 / step: the ants know nothing but their cell
  double evaporation = 0.1;         ///< rho: fraction of every trail lost per iteration
  double deposit = 1.0;             ///< Q: an ant lays Q / (route length) on each of its steps
  double exploitation = 0.0;        ///< q0: chance of taking the strongest step outright
  double initial_pheromone = 0.01;  ///< trail on every step before any ant walked
  double min_pheromone = 1e-6;      ///< floor, so that no step ever becomes impossible
  bool elite_deposit = true;        ///< the best route so far is reinforced every iteration
  int max_steps = 0;                ///< moves before an ant gives up (0: 4 x walkable cells)
  std::uint64_t seed = 1;           ///< random stream of the colony
};

/// Summary of one iteration.
struct AntIteration {
  int found = 0;             ///< ants that reached the food
  double mean_length = 0.0;  ///< mean route length of those ants
  double best_length = 0.0;  ///< best route length found so far (0 while none)
};

/// A colony exploring one map from a nest toward food it has not seen.
class AntColony {
 public:
  /// A colony on `map` (which must outlive it) between two walkable cells.
  AntColony(const ai::GridMap& map, ai::Cell nest, ai::Cell food,
            const AntColonySettings& settings);

  /// Sends one iteration of ants, then evaporates and deposits.
  AntIteration iterate();
  /// Length of the best route (0 while none).
  double best_length() const { return best_length_; }
  /// The colony's current preferred route: from the nest, always the strongest unvisited
  /// step; false when it dead-ends or loops without reaching the food.
  bool trailRoute(std::vector<ai::Cell>& out) const;
  /// Trail on the step from `c` in direction k (0..7).
  double pheromone(ai::Cell c, int k) const {
    return tau_[std::size_t(map_.index(c.x, c.y)) * 8 + k];
  }

 private:
  bool walk(AntTrip& trip);

  const ai::GridMap& map_;
  ai::Cell nest_, food_;
  AntColonySettings settings_;
  AntTripRule trips_;  // for decide(): walk() ends the walks, by its own count of moves
  Pcg32 rng_;
  std::vector<double> tau_;          // 8 directed steps per cell
  AntTrip trip_;                     // the walking ant's
  std::vector<std::uint32_t> seen_;  // stamp per cell: on trip_'s route or dead ends
  std::uint32_t stamp_ = 0;
  std::vector<ai::Cell> best_;
  double best_length_ = 0.0;
  std::vector<std::vector<ai::Cell>> routes_;  // this iteration's successful routes
};

}  // namespace zonesim::crowd
