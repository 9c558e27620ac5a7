#pragma once
// The scene's `time_dilation` key (docs/scene-format.md); internal to the scene loader.

#include "common/scene_loader_node.h"
#include "common/scene_time_dilation.h"

namespace zonesim {

/// Reads the optional top-level `time_dilation` key (absent: off, with the defaults).
void readTimeDilation(const SceneMap& root, TimeDilationSettings& td);

}  // namespace zonesim
