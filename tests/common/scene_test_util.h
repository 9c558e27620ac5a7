#pragma once
// Helpers shared by the scene tests: paths into the source tree and the message of a
// SceneError.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "common/scene.h"

namespace zonesim::test {

/// A path inside the source tree (scenes/, tests/data/).
inline std::string sourcePath(const std::string& relative) {
  return std::string(ZONESIM_SOURCE_DIR) + "/" + relative;
}

/// Names (without .yaml) of the YAML files in a source folder, sorted: test parameters.
inline std::vector<std::string> yamlStems(const std::string& folder) {
  std::vector<std::string> stems;
  for (const auto& entry : std::filesystem::directory_iterator(sourcePath(folder))) {
    if (entry.path().extension() == ".yaml") stems.push_back(entry.path().stem().string());
  }
  std::sort(stems.begin(), stems.end());
  return stems;
}

/// The what() of the SceneError that `load` throws; a test failure if it throws nothing.
inline std::string sceneError(const std::function<void()>& load) {
  try {
    load();
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError thrown";
  return {};
}

}  // namespace zonesim::test
