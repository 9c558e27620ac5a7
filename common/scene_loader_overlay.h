#pragma once
// Overlay scene files: a file whose first key is `overlay_of: BASE` holds only what it changes
// (the tuner writes these). Its mappings merge into the base scene's key by key, any other
// value replaces the base's, and every merged value remembers the file it came from, so an
// error in it names the overlay's file:line and a relative path in it resolves beside the
// overlay. Internal to the scene loader.

#include <yaml-cpp/yaml.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace zonesim {

/// Where a value an overlay put in was written: its file and the line of its key.
struct OverlaidAt {
  const std::string* file;
  int key_line;  ///< 1-based
};

/// Which values of a merged document came from which file (other than the root's).
struct SceneOrigins {
  struct Entry {
    YAML::Node value;
    std::unique_ptr<std::string> file;  ///< owned here: nodes point at these strings
    int key_line;
  };
  /// The file of the document the others were merged into: the base scene at the bottom.
  std::string root_file;
  /// Each value an overlay put in.
  std::vector<Entry> overlaid;

  /// Where `value` was written if an overlay put it in, else nothing.
  std::optional<OverlaidAt> find(const YAML::Node& value) const;
};

/// Parses scene text named `file`; when it is an overlay, loads its base (a path relative to
/// `file`), recursively, and merges. Throws SceneError on an unreadable or circular base.
YAML::Node parseSceneWithOverlays(const std::string& text, const std::string& file,
                                  SceneOrigins& origins);

}  // namespace zonesim
