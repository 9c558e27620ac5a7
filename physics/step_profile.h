#pragma once
// Where a world step spends its time, stage by stage (Box2D's b2Profile): the zone reports it
// per tick as physics.<stage>, so a slow step shows which stage grew.

namespace zonesim::physics {

/// Seconds spent in each stage of the last World::step (all substeps together).
struct StepProfile {
  double integrate = 0;    ///< forces into velocities, and the non-finite checks
  double broadphase = 0;   ///< proxy boxes and candidate pairs
  double narrowphase = 0;  ///< contacts of the candidate pairs and the ground planes
  double prepare = 0;      ///< warm start and solver and joint rows
  double solve = 0;        ///< velocity and position iterations, positions integrated
  double islands = 0;      ///< islands and sleeping
};

}  // namespace zonesim::physics
