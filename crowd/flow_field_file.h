#pragma once
// Flow fields stored with their map (the seed's "embedded map data"): a command builds the
// fields of a scene's fixed destinations once (zone_node/tools/bake_fields.cpp) and the zones
// load them instead of building them at start. The file holds the map's fingerprint, so fields
// built for another map, or for this one before it was edited, are refused rather than used.
//
// Format (little-endian): "ZSFLOW1\n", u32 width, u32 height, u64 map fingerprint, u32 field
// count, then per field i32 goal x, i32 goal y, width x height f32 distances and as many i8
// directions, row by row.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "ai/grid_map.h"
#include "crowd/flow_field.h"

namespace zonesim::crowd {

/// The map's size and the passability of every cell, hashed (FNV-1a 64).
std::uint64_t mapFingerprint(const ai::GridMap& map);

/// Writes `fields`, all built on `map`, to `path`. Throws std::runtime_error naming the path.
void writeFlowFields(const std::string& path, const ai::GridMap& map,
                     std::span<const FlowField* const> fields);

/// The fields stored at `path` for `map`. Throws std::runtime_error naming the path when it
/// cannot be read, is not a fields file, is cut short, or was built for another map.
std::vector<std::unique_ptr<FlowField>> readFlowFields(const std::string& path,
                                                       const ai::GridMap& map);

}  // namespace zonesim::crowd
