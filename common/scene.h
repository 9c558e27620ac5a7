#pragma once
// A scene: everything a run needs to know about the world, loaded from a YAML file.
// Plain data only; loadScene() validates every field and reports file:line: field: problem.
// Each section has a header of its own (common/scene_<section>.h): a file that reads one section
// includes that one, and a header that only names Scene forward-declares it, so that adding a key
// to a section rebuilds only what reads that section.

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/scene_adaptation.h"
#include "common/scene_agents.h"
#include "common/scene_clients.h"
#include "common/scene_dead_reckoning.h"
#include "common/scene_emitters.h"
#include "common/scene_geometry.h"
#include "common/scene_interactions.h"
#include "common/scene_interest.h"
#include "common/scene_lod.h"
#include "common/scene_map.h"
#include "common/scene_npcs.h"
#include "common/scene_physics.h"
#include "common/scene_time_dilation.h"
#include "common/scene_zones.h"

namespace zonesim {

/// A whole scene; the docs for every key are in docs/scene-format.md.
struct Scene {
  std::string name;
  std::string source_path;  ///< file it was loaded from; empty from parseScene()
  SceneBox world;
  double tick_rate = 30;  ///< ticks per second of wall time when running real-time
  double dt = 1.0 / 30;   ///< simulated seconds per tick
  std::uint64_t seed = 1;
  SceneZones zones;
  double interest_cell_size = 50;  ///< metres; one DDS partition per cell
  int keyframe_every = 90;         ///< ticks between per-cell keyframes
  double halo_width = 10;
  /// Slack past the width that lets halo send lists live for several ticks of motion;
  /// absent: haloSkin()'s default.
  std::optional<double> halo_skin;
  DeadReckoning dead_reckoning;
  PhysicsSettings physics;
  std::vector<NpcPopulation> npcs;
  std::vector<RigidBodyPopulation> rigid_bodies;
  std::vector<EmitterPopulation> emitters;
  ClientProfile clients;
  AuraNimbus aura_nimbus;              ///< keys in the interest section
  ObstacleMap map;                     ///< walls and open ground for crowds and path finding
  AgentSettings agents;                ///< AI agent types and populations (common/scene_agents.h)
  CrowdLod lod;                        ///< level of detail of the crowd systems
  TimeDilationSettings time_dilation;  ///< slowing the clock under overload
  InteractionSettings interactions;    ///< hits and gifts between entities, by message
  AdaptationSettings adaptation;       ///< duels against NPCs that adapt to the player
  /// Where particles and flocks step: off, on, auto or probe (zone_node's --gpu, whose default
  /// `scene` takes this; the key gpu.mode, absent: auto).
  std::string gpu_mode = "auto";
};

/// The halo skin the zones use: `halo.skin`, or by default max(1 m, width / 5), enough that
/// walkers keep their send lists for a few ticks without sending many more ghosts.
inline double haloSkin(const Scene& scene) {
  const double fifth = 0.2 * scene.halo_width;
  return scene.halo_skin.value_or(fifth > 1.0 ? fifth : 1.0);
}

/// A scene file problem; what() is "file:line: field: what is wrong".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Loads and validates a scene file; throws SceneError on the first problem.
Scene loadScene(const std::string& path);

/// Parses scene text (the name is used in error messages as the file).
Scene parseScene(const std::string& text, const std::string& name);

}  // namespace zonesim
