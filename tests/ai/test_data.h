#pragma once
// Paths to the shipped Moving AI maps, found from the source tree wherever the build is.

#include <string>

namespace zonesim::ai::test {

/// Full path of a file under tests/data/movingai/.
inline std::string movingAiPath(const std::string& name) {
  return std::string(ZONESIM_SOURCE_DIR) + "/tests/data/movingai/" + name;
}

}  // namespace zonesim::ai::test
