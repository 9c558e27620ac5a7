#pragma once
// Any-angle aims for a flow crowd on a navigation mesh (map.navigation: navmesh). A grid flow
// field sends an agent to the centre of the next cell of an 8-connected path, so crowds walk
// octile zig-zags; here each cell of the mesh gets the first corner of the funnelled mesh path
// from its centre to the goal, the point the agent can walk to in a straight line. The mesh is
// built without erosion, so every open cell has an aim; the agent radius is kept instead by
// moving each corner off the end of the wall it bends round (an eroded mesh left a band along
// the walls without aims, where agents followed the grid's octile steps and zig-zagged in and
// out of it: slower than the grid field alone).

#include <vector>

#include "ai/grid_map.h"
#include "ai/navmesh.h"
#include "crowd/flow_field.h"

namespace zonesim::crowd {

/// Per cell of the mesh's map, row-major, two floats (map units): the first corner of the
/// funnelled path from the cell's centre to the centre of the field's goal, moved `clearance`
/// (map units) away from the wall it bends round along both axes; NaN where the cell is off
/// the mesh or the field does not reach the goal from it. The corridor is the polygons the
/// grid field's own path from the cell crosses, pulled taut up to its first corner
/// (ai::StringPuller: the rest of the corridor is not read): so the aims
/// choose between routes as the field's exact distances do. Corridors planned over the mesh
/// (ai::NavMeshSearch, not exact over all corridors) chose differently in neighbouring cells
/// near a tie, and a crowd gathered on the ridge between them for good. The goal's polygon
/// aims at the goal. A moved corner that `walls` (the mesh's map with its boxes closed; null:
/// not checked) hides from the cell's centre is left where the path bends. Throws
/// std::invalid_argument when the goal is off the mesh.
std::vector<float> navMeshWaypoints(const ai::NavMesh& mesh, const FlowField& field,
                                    double clearance = 0, const ai::GridMap* walls = nullptr);

}  // namespace zonesim::crowd
