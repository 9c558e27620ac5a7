#pragma once
// The scene's `lod` key: level of detail for crowds.

#include <utility>
#include <vector>

namespace zonesim {

/// Level of detail for crowds (crowd/lod.h): NPCs far from every player are updated
/// less often, the farthest without steering, and far rigid bodies too (`lod:` key; absent:
/// every NPC and body every tick).
struct CrowdLod {
  bool enabled = false;     ///< the scene has a `lod` key, and it does not say enabled: false
  double near_radius = 40;  ///< m from the nearest player: every tick, full steering
  double far_radius = 120;  ///< m: between near and far, every `mid_every` ticks
  int mid_every = 2;        ///< ticks between updates of the middle band
  int far_every = 8;        ///< ticks between updates beyond far_radius
  bool mid_steers = true;   ///< the middle band keeps its neighbour terms
  bool far_steers = false;  ///< the far band follows its field only
  /// Agents in a cell (crowded_cell m square) holding at least this many update at full
  /// detail wherever they are (crowd::LodSettings::crowded_count); 0: off.
  int crowded_count = 0;
  double crowded_cell = 4;  ///< m
  /// Rigid-body islands with no body within near_radius of a player or observer step every
  /// this many ticks, by the time they skipped (physics/step_lod.h); 1: every tick.
  int physics_every = 1;
  /// s: the longest step a far island takes (physics::WorldSettings::lod_longest_step); 0: any.
  double physics_max_step = 1.0 / 15.0;
  /// Fixed ground-plane points (x, z) that count as players (scripted observers: runs
  /// without clients, tests, points of interest that keep full detail).
  std::vector<std::pair<double, double>> observers;
};

}  // namespace zonesim
