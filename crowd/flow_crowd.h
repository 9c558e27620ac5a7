#pragma once
// Many agents heading to a few destinations over shared flow fields. Each agent aims at the
// centre of the next cell its field gives for the cell it stands in (so agents drift to cell
// centres and clear wall corners), slows down inside a radius of the goal, and is pushed
// apart from close neighbours (owned and ghosts) by a separation term summed in the grid's
// canonical order. Moves never enter blocked cells (they slide along walls). With a body
// radius, agents are discs that never step into each other (keep_apart.h).

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "ai/grid_map.h"
#include "ai/navmesh.h"
#include "crowd/agents.h"
#include "crowd/flow_field.h"
#include "crowd/keep_apart.h"
#include "crowd/map_frame.h"
#include "crowd/neighbour_grid.h"
#include "crowd/step_plan.h"

namespace zonesim::crowd {

/// Flow-field following parameters; lengths in metres, times in seconds.
struct FlowCrowdSettings {
  double max_speed = 2.0;           ///< m/s
  double max_force = 10.0;          ///< m/s^2, bound on the steering acceleration
  double steer_rate = 4.0;          ///< 1/s: rate at which velocity follows the field
  double separation_radius = 0.6;   ///< neighbours closer than this push apart
  double separation_weight = 10.0;  ///< 1/s^2 per unit of (radius / distance - 1)
  double arrive_radius = 0.75;      ///< an agent this close to its goal's centre has arrived
  double slow_radius = 2.0;         ///< inside this distance of the goal, speed ramps down
  /// Side of the neighbour grid's cells (at least the separation radius). Larger than the
  /// radius because the grid's per-step cost grows with the cells of the occupied box, which
  /// dominates for sparse crowds on big maps; every rank must use the same value (it fixes
  /// the order of the separation sums).
  double grid_cell = 2.0;
  /// Agents are discs of this radius that never step into each other (keep_apart.h); 0: they
  /// may overlap, kept apart by separation alone. Holds for agents at full steering detail.
  double body_radius = 0.0;
  /// How far the caller shows every agent its neighbours (the zone's halo width): an agent
  /// keeping its gaps moves at most (sight - 2 body_radius) / 2 a step, so that every
  /// neighbour that could bind it is seen on every rank. Must exceed 2 body_radius.
  double sight = 1e9;
  /// Aim at the first corner of the funnelled navigation-mesh path to the goal
  /// (crowd/flow_waypoints.h) instead of the next cell's centre, on a mesh of the map built
  /// with `navmesh_config` and closing `navmesh_boxes` (map units); false: the grid field alone.
  bool navmesh = false;
  ai::NavMeshConfig navmesh_config;
  std::vector<ai::NavBox> navmesh_boxes;
};

/// Steps agents along shared flow fields on one map.
class FlowCrowd {
 public:
  /// Agents on `map` placed at `frame` in the world; the map must outlive the crowd.
  FlowCrowd(const ai::GridMap& map, const MapFrame& frame, const FlowCrowdSettings& settings);

  /// Builds the field for a goal cell once; returns its destination index.
  int addDestination(ai::Cell goal);
  /// Adds a field built earlier on this map (crowd/flow_field_file.h); returns its index.
  int addDestination(std::unique_ptr<FlowField> field);
  /// Rebuilds every field whose map version is stale (a door opened or closed).
  int refreshFields();
  /// Number of destinations.
  int destinationCount() const { return int(fields_.size()); }
  /// The field of destination `d`.
  const FlowField& field(int d) const { return *fields_[d]; }

  /// Advances the agents by `dt`. `dest[i]` is agent i's destination index; `arrived[i]` is
  /// set to 1 when the agent reaches its goal; arrived agents have left the crowd: they are
  /// neither moved nor seen by the others (the caller may remove them or give them a new
  /// destination and clear the flag). `ghosts` push by separation but are not moved.
  /// `plan`: per-agent dt and detail (lod.h); agents with steer 0 follow the field without
  /// separation (no neighbour query).
  void step(const AgentSpan& agents, std::span<const std::uint16_t> dest,
            std::span<std::uint8_t> arrived, const GhostSpan& ghosts, double dt,
            const StepPlan& plan = {});

  /// The velocity the field asks for at `pos` toward destination `d` (zero where unreachable).
  Vec2 desiredVelocity(Vec2 pos, int d) const;
  /// True when `pos` is within the arrival radius of destination `d`.
  bool hasArrived(Vec2 pos, int d) const;
  /// The settings in use.
  const FlowCrowdSettings& settings() const { return settings_; }
  /// The map frame.
  const MapFrame& frame() const { return frame_; }
  /// The grid of the last step: the agents still walking, at their positions before it.
  const NeighbourGrid& grid() const { return grid_; }

 private:
  // self: the agent's index in grid_.entries(); `gaps` (if any) gathers the neighbours whose
  // gaps may bind it.
  Vec2 separation(std::int32_t self, KeepApart* gaps) const;
  // desiredVelocity, defined inline for the step; `cell` is set to the cell of `pos`.
  Vec2 desiredVelocityAt(Vec2 pos, int d, ai::Cell& cell) const;
  bool leaveClosedCell(const FlowField& f, ai::Cell c, ai::Cell& next) const;
  // Where an agent at `from` ends when it keeps the gaps gathered in keep_apart_, given where
  // its steering took it (`to`, velocity `vel`, updated to the move it makes).
  Vec2 keepGaps(Vec2 from, Vec2 to, double h, Vec2& vel) const;
  // With settings_.navmesh: gives `field` its aims on the mesh of the map as it is now.
  void aimOnMesh(FlowField& field);

  const ai::GridMap& map_;
  MapFrame frame_;
  FlowCrowdSettings settings_;
  std::vector<std::unique_ptr<FlowField>> fields_;
  std::unique_ptr<ai::NavMesh> mesh_;        // settings_.navmesh: the map's mesh at mesh_version_
  std::unique_ptr<ai::GridMap> mesh_walls_;  // the map with the mesh's boxes closed
  std::uint64_t mesh_version_ = 0;
  NeighbourGrid grid_;
  KeepApart keep_apart_;  // the gaps of the agent being stepped
};

}  // namespace zonesim::crowd
