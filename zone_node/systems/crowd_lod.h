#pragma once
// The scene's `lod` key as the crowd library's level-of-detail settings, one conversion shared
// by the crowd systems that apply it (flocks and flow crowds).

#include "common/scene_lod.h"
#include "crowd/lod.h"

namespace zonesim::zone {

/// crowd::LodSettings from the scene's `lod` block.
crowd::LodSettings lodOf(const CrowdLod& lod);

}  // namespace zonesim::zone
