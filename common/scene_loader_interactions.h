#pragma once
// The scene's `interactions` key (docs/scene-format.md); internal to the scene loader.

#include "common/scene_interactions.h"
#include "common/scene_loader_node.h"

namespace zonesim {

/// Reads the optional top-level `interactions` key (absent: off). `halo_width`: the halo the
/// scene gives its zones; a reach beyond it would miss targets across a border. Items lie
/// inside `world`.
void readInteractions(const SceneMap& root, const SceneBox& world, double halo_width,
                      InteractionSettings& in);

}  // namespace zonesim
