#pragma once
// One ant's trip as plain data, so that it can ride in an entity (zone_node's AntData) and
// migrate with it; crowd/ant_trip_rule.h is the rule that moves it on.

#include <cstdint>
#include <vector>

namespace zonesim::crowd {

/// What an ant is doing (AntTrip::mode).
enum class AntMode : std::int32_t {
  Searching = 0,  ///< walking away from the nest, looking for the food
  Returning = 1,  ///< walking its route back to the nest (laying trail if it found food)
};

/// One ant's trip. Cells are x, y pairs of int32, and the mode an int32, as the migration
/// record carries them.
struct AntTrip {
  std::int32_t mode = 0;                ///< AntMode
  std::int32_t route_at = 0;            ///< index (in cells) of the next cell of `route` back
  double route_length = 0;              ///< m: length of the route found (0: none yet)
  std::vector<std::int32_t> route;      ///< cells from the nest as x, y pairs
  std::vector<std::int32_t> dead_ends;  ///< dead ends of this trip, x, y pairs

  bool operator==(const AntTrip&) const = default;
};

}  // namespace zonesim::crowd
