#pragma once
// Where a scene came from, for "file:line: ..." errors raised after loading (by the systems
// that build on a scene), without the whole scene header.

#include <string>

namespace zonesim {

struct Scene;

/// The file the scene was loaded from, or its name when it was parsed from text.
std::string sceneFile(const Scene& scene);

}  // namespace zonesim
