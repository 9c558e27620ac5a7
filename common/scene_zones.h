#pragma once
// The scene's `zones` key (docs/scene-format.md): how many zones, and how they are placed.

namespace zonesim {

/// The `zones:` key: how the ground plane is split among zone ranks (the class that holds the
/// split at run time is zone::ZoneLayout).
struct SceneZones {
  /// Grid: even columns x rows. Rcb: the same shape, with column and row boundaries placed by
  /// recursive coordinate bisection so each zone starts with an equal share of the entities.
  enum class Kind { Grid, Rcb };
  Kind kind = Kind::Grid;
  int columns = 1;  ///< zones along x
  int rows = 1;     ///< zones along z
};

}  // namespace zonesim
