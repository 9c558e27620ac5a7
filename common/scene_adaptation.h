#pragma once
// The scene's `adaptation` key: duels between simulated players and NPCs that adapt to them
// (ai/adapt/, zone_node/systems/duels.h).

#include <string>
#include <vector>

namespace zonesim {

/// One simulated player duelling one adaptive NPC, at an arena on the ground.
struct DuelSpec {
  double skill = 0.5;   ///< the player's hidden skill, 0 weak to 1 strong
  double x = 0, z = 0;  ///< the arena; the zone holding it at the start runs the duel
};

/// How NPCs adapt to the players they duel (docs/scene-format.md).
struct AdaptationSettings {
  enum class Mode { Off, RubberBand, Model };
  bool enabled = false;          ///< on when the scene has the section
  Mode mode = Mode::Model;       ///< who proposes the next NPC
  std::string model;             ///< model file, resolved against the scene's folder
  double target_win_rate = 0.5;  ///< the share of rounds players should win
  double max_step = 0.1;         ///< fraction of a parameter's range it may move per round
  int band_window = 10;          ///< rounds the rubber band looks back over
  double band_gain = 0.5;        ///< difficulty per unit of the player's lead
  std::vector<DuelSpec> duels;
};

}  // namespace zonesim
