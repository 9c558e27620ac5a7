#pragma once
// The scene's `adaptation` key (docs/scene-format.md); internal to the scene loader.

#include <string>

#include "common/scene_adaptation.h"
#include "common/scene_loader_node.h"

namespace zonesim {

/// Reads the optional top-level `adaptation` key (absent: off, nothing runs). The model path
/// resolves against the folder of the file that names it; arenas lie inside `world`.
void readAdaptation(const SceneMap& root, const SceneBox& world, AdaptationSettings& a);

}  // namespace zonesim
