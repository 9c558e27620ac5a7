#pragma once
// Fixed groups (the seed's workflow): slots arranged around a centre; A* plans the centre's
// route and the centre moves along it; each member steers toward its slot with the centre's
// velocity as feed-forward, so the pull fades as the centre slows into its destination. A
// member that is cut off (no line of sight to the centre, or too far from its slot, e.g. it
// went into a building) plans its own A* path back to the centre, follows it, and switches
// back to its slot once it sees the slot and is close: the seed's remedy.

#include <cstdint>
#include <span>
#include <vector>

#include "zone_node/ai/grid_map.h"
#include "zone_node/ai/grid_search.h"
#include "zone_node/crowd/map_frame.h"

namespace zonesim::crowd {

/// Formation parameters; lengths in metres, times in seconds.
struct FormationSettings {
  double centreSpeed = 1.5;        ///< m/s of the centre along its path
  double memberMaxSpeed = 2.5;     ///< m/s; above the centre's so members can catch up
  double maxForce = 8.0;           ///< m/s^2, bound on a member's steering acceleration
  double steerRate = 4.0;          ///< 1/s: rate at which velocity follows the desired one
  double slotGain = 2.0;           ///< 1/s: desired velocity per metre of slot error
  double slowRadius = 3.0;         ///< the centre slows down this close to its destination
  double turnRate = 3.0;           ///< 1/s: how fast the formation's heading follows the path
  double cutOffDistance = 5.0;     ///< a member this far from its slot is cut off
  double rejoinDistance = 1.0;     ///< a rejoining member this close to a visible slot rejoins
  double replanDistance = 2.0;     ///< re-plan a rejoin path when the centre moved this far
  double waypointRadius = 0.4;     ///< a rejoin waypoint this close counts as reached
  double separationRadius = 0.6;   ///< members closer than this push apart
  double separationWeight = 10.0;  ///< 1/s^2 per unit of (radius / distance - 1)
};

/// What a member is doing.
enum class MemberMode : std::uint8_t {
  InFormation = 0,  ///< steering to its slot
  Rejoining = 1,    ///< following its own A* path back to the group
};

/// One fixed group on a grid map; members are indexed like the slot offsets.
class Formation {
 public:
  /// `slotOffsets` are in the formation's frame (x ahead, y to the left of the heading);
  /// `centre` must be walkable. The map must outlive the formation.
  Formation(const ai::GridMap& map, const MapFrame& frame, const FormationSettings& settings,
            std::vector<Vec2> slotOffsets, Vec2 centre);

  /// Plans the centre's route to `goal` with A*; false (and the centre stays) when unreachable.
  bool setDestination(Vec2 goal);
  /// Moves the centre along its route and steps every member (pos/vel per slot).
  void step(std::span<Vec2> pos, std::span<Vec2> vel, double dt);

  /// Current centre.
  Vec2 centre() const { return centre_; }
  /// Current heading (unit vector).
  Vec2 heading() const { return heading_; }
  /// World position of slot i now.
  Vec2 slotPosition(int i) const;
  /// Mode of member i.
  MemberMode mode(int i) const { return members_[i].mode; }
  /// True when the centre has reached the end of its route.
  bool centreArrived() const { return routeDone_; }
  /// Number of rejoin paths planned so far (A* calls for members).
  int rejoinPlans() const { return rejoinPlans_; }
  /// Number of members.
  int size() const { return int(slots_.size()); }

 private:
  struct Member {
    MemberMode mode = MemberMode::InFormation;
    std::vector<Vec2> path;  // rejoin waypoints (cell centres), start first
    std::size_t at = 0;      // next waypoint
    Vec2 plannedFor;         // centre position the path was planned to
  };

  void moveCentre(double dt);
  void updateMode(int i, Vec2 pos);
  bool planRejoin(int i, Vec2 pos);
  Vec2 desiredVelocity(int i, Vec2 pos);
  Vec2 separation(int i, std::span<const Vec2> pos) const;

  const ai::GridMap& map_;
  MapFrame frame_;
  FormationSettings settings_;
  std::vector<Vec2> slots_;
  std::vector<Member> members_;
  ai::GridSearch search_;
  ai::GridPath scratch_;
  std::vector<Vec2> route_;  // centre's waypoints
  std::size_t routeAt_ = 0;  // index of the waypoint the centre is heading to
  bool routeDone_ = true;
  Vec2 centre_, centreVel_, heading_{1.0, 0.0};
  int rejoinPlans_ = 0;
  std::vector<Vec2> snapshot_;  // positions at the start of the step (members read these)
};

}  // namespace zonesim::crowd
