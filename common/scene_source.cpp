#include "common/scene_source.h"

#include "common/scene.h"

namespace zonesim {

std::string sceneFile(const Scene& scene) {
  return scene.source_path.empty() ? scene.name : scene.source_path;
}

}  // namespace zonesim
