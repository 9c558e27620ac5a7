#pragma once
// The rule of one ant's trip, tick by tick, for ants that walk from cell centre to cell centre
// (the zone's ant colonies, zone_node/systems/ant_movement.h). A searching ant senses only the
// cells next to it, never re-enters a cell of its trip (its route and its dead ends), picks
// its next cell by chooseAntStep (crowd/ant_step.h), and backs off one cell from a dead end
// (at the nest it forgets its dead ends and tries again). At the food, or after max_steps
// route cells, it turns home on a shortened route; walking it back it lays trail if it found
// food. The trip is plain data (crowd/ant_trip.h) and every choice depends only on the trip,
// the trail and the draws the caller passes, so an ant walks alike on whichever rank holds it.

#include <cstdint>
#include <vector>

#include "ai/grid_map.h"
#include "ai/octile.h"
#include "crowd/ant_step.h"
#include "crowd/ant_trail.h"
#include "crowd/ant_trip.h"
#include "crowd/grid_step.h"

namespace zonesim::crowd {

/// Number of cells in a list of x, y pairs.
inline std::int32_t routeCellCount(const std::vector<std::int32_t>& cells) {
  return std::int32_t(cells.size() / 2);
}
/// Cell k of a list of x, y pairs.
inline ai::Cell routeCell(const std::vector<std::int32_t>& cells, std::int32_t k) {
  return {cells[std::size_t(2 * k)], cells[std::size_t(2 * k + 1)]};
}
/// A list of x, y pairs as cells.
std::vector<ai::Cell> routeCells(const std::vector<std::int32_t>& cells);
/// Length (m) of a route of neighbouring cells: the octile distances of its steps, in order.
double routeLength(const std::vector<std::int32_t>& route);

/// The parameters of a colony's trips.
struct AntTripSettings {
  AntChoice choice;    ///< the step choice
  double deposit = 1;  ///< Q: an ant home from the food lays Q / (route length) on every cell
  int max_steps = 0;   ///< route cells before a searching ant gives up (0: 4 x walkable cells)
};

/// How a searching ant's decision went (AntTripRule::decide).
enum class AntDecision {
  Moved,       ///< it added its next cell to its route
  BackedOff,   ///< a dead end: remembered, and the ant stepped back one cell
  StuckAtNest  ///< a dead end at the nest: the ant forgot its dead ends to try again
};

/// What an ant did at a cell centre (AntTripRule::arrive).
struct AntArrival {
  ai::Cell cell;           ///< the centre it stood on
  std::int64_t laid = 0;   ///< trail units it laid on that cell
  double trip_length = 0;  ///< > 0: it came home from the food, by a route this long (m)
};

/// The trips of one colony between its nest and its food.
class AntTripRule {
 public:
  /// Trips on `map` (which must outlive it) between two walkable cells.
  AntTripRule(const ai::GridMap& map, ai::Cell nest, ai::Cell food,
              const AntTripSettings& settings);

  /// Where the ants start and end their trips.
  ai::Cell nest() const { return nest_; }
  /// What they look for.
  ai::Cell food() const { return food_; }
  /// Route cells before a searching ant gives up (max_steps resolved).
  int max_steps() const { return max_steps_; }

  /// An ant with no route yet stands at the nest.
  void begin(AntTrip& trip) const;
  /// The cell centre the ant walks to: its route's last cell while searching, the next one
  /// back while returning.
  ai::Cell target(const AntTrip& trip) const;
  /// Whether a searching ant may step onto n: not on its route, not one of its dead ends.
  bool open(const AntTrip& trip, ai::Cell n) const;

  /// At the cell centre target(trip): a returning ant lays trail and steps home; a searching
  /// one at the food (while `food_there`) or past max_steps turns home; else it decides its
  /// next cell reading `trail` as it stands, with draws uniform(i) in [0, 1).
  template <typename Uniform>
  AntArrival arrive(AntTrip& trip, const AntTrail& trail, bool food_there, Uniform&& uniform) const;
  /// A searching ant at its route's last cell picks its next cell (chooseAntStep with
  /// trail(k, n) and uniform(i)), or backs off from a dead end.
  template <typename Trail, typename Uniform>
  AntDecision decide(AntTrip& trip, Trail&& trail, Uniform&& uniform) const {
    return decide(
        trip, trail, [&](ai::Cell n) { return open(trip, n); }, uniform);
  }
  /// The same with open(n) in place of open(trip, n), for a caller that keeps the cells of the
  /// trip in a faster form (AntColony: a stamp per cell); it must say the same.
  template <typename Trail, typename Open, typename Uniform>
  AntDecision decide(AntTrip& trip, Trail&& trail, Open&& open, Uniform&& uniform) const;
  /// At a dead end: remember it and back off one cell; at the nest forget the dead ends.
  AntDecision backOff(AntTrip& trip) const;
  /// Found the food or gave up: the ant turns home on its shortened route, which it will lay
  /// trail on only when `found`.
  void turnHome(AntTrip& trip, bool found) const;
  /// A returning ant steps one cell back; true when it was home, and has started a new trip.
  bool stepHome(AntTrip& trip) const;
  /// Starts a new trip from the nest.
  void restart(AntTrip& trip) const;
  /// Replaces `route` (x, y pairs, nest first) by the way home from its last cell that always
  /// steps to the earliest route cell next to the current one: the detours of the way out are
  /// cut, since the ant remembers its route and senses its neighbours.
  void shorten(std::vector<std::int32_t>& route) const;

 private:
  bool adjacent(ai::Cell a, ai::Cell b) const;

  const ai::GridMap& map_;
  ai::Cell nest_, food_;
  AntChoice choice_;
  double deposit_;
  int max_steps_;
};

template <typename Uniform>
AntArrival AntTripRule::arrive(AntTrip& trip, const AntTrail& trail, bool food_there,
                               Uniform&& uniform) const {
  AntArrival out{target(trip)};
  const ai::Cell c = out.cell;
  if (trip.mode == std::int32_t(AntMode::Returning)) {
    const double length = trip.route_length;
    if (length > 0) out.laid = trailDepositUnits(deposit_, length);
    if (stepHome(trip) && length > 0) out.trip_length = length;
  } else if ((c == food_ && food_there) || routeCellCount(trip.route) > max_steps_) {
    const bool found = c == food_ && food_there;
    turnHome(trip, found);
    if (found) out.laid = trailDepositUnits(deposit_, trip.route_length);
  } else {
    decide(
        trip, [&](int, ai::Cell n) { return trail.at(n); }, uniform);
  }
  return out;
}

template <typename Trail, typename Open, typename Uniform>
AntDecision AntTripRule::decide(AntTrip& trip, Trail&& trail, Open&& open,
                                Uniform&& uniform) const {
  const ai::Cell c = routeCell(trip.route, routeCellCount(trip.route) - 1);
  const int k = chooseAntStep(map_, c, food_, choice_, trail, open, uniform);
  if (k < 0) return backOff(trip);
  const ai::Cell n = gridStep(c, k);
  trip.route.push_back(n.x);
  trip.route.push_back(n.y);
  return AntDecision::Moved;
}

}  // namespace zonesim::crowd
