#pragma once
// The one YAML document of a scene file, parsed with every yaml-cpp failure turned into
// SceneError "file:line: yaml: ..." (or "document" for an empty or multi-document file).
// Internal to the scene loader.

#include <yaml-cpp/yaml.h>

#include <string>

namespace zonesim {

/// Parses `text`; throws SceneError naming `file` unless it holds exactly one document.
YAML::Node parseSceneDocument(const std::string& text, const std::string& file);

}  // namespace zonesim
