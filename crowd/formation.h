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

#include "ai/grid_map.h"
#include "ai/grid_search.h"
#include "crowd/map_frame.h"

namespace zonesim::ai {
class NavMeshSearch;
}  // namespace zonesim::ai

namespace zonesim::crowd {

/// Formation parameters; lengths in metres, times in seconds.
struct FormationSettings {
  double centre_speed = 1.5;        ///< m/s of the centre along its path
  double member_max_speed = 2.5;    ///< m/s; above the centre's so members can catch up
  double max_force = 8.0;           ///< m/s^2, bound on a member's steering acceleration
  double steer_rate = 4.0;          ///< 1/s: rate at which velocity follows the desired one
  double slot_gain = 2.0;           ///< 1/s: desired velocity per metre of slot error
  double slow_radius = 3.0;         ///< the centre slows down this close to its destination
  double turn_rate = 3.0;           ///< 1/s: how fast the formation's heading follows the path
  double cut_off_distance = 5.0;    ///< a member this far from its slot is cut off
  double rejoin_distance = 1.0;     ///< a rejoining member this close to a visible slot rejoins
  double replan_distance = 2.0;     ///< re-plan a rejoin path when the centre moved this far
  double waypoint_radius = 0.4;     ///< a rejoin waypoint this close counts as reached
  double separation_radius = 0.6;   ///< members closer than this push apart
  double separation_weight = 10.0;  ///< 1/s^2 per unit of (radius / distance - 1)
};

/// What a member is doing.
enum class MemberMode : std::uint8_t {
  InFormation = 0,  ///< steering to its slot
  Rejoining = 1,    ///< following its own A* path back to the group
};

/// The formation's centre: its route, where it is, how fast it goes and where it faces. It
/// depends only on the route, the settings and the steps taken, so every copy stepped alike
/// (e.g. one per rank) holds bitwise the same centre.
class FormationCentre {
 public:
  /// A centre at rest at `at`, facing `heading` (a unit vector).
  FormationCentre(const FormationSettings& settings, Vec2 at, Vec2 heading = {1.0, 0.0});

  /// Makes the centre walk `route` (its points in order; the first should be where it is).
  void setRoute(std::vector<Vec2> route);
  /// Moves the centre along its route by one step of `dt` and turns its heading.
  void advance(double dt);

  /// Current position.
  Vec2 position() const { return at_; }
  /// Velocity over the last step.
  Vec2 velocity() const { return vel_; }
  /// Current heading (unit vector).
  Vec2 heading() const { return heading_; }
  /// True when the centre has reached the end of its route (or has none).
  bool arrived() const { return done_; }
  /// The route's points, in order.
  const std::vector<Vec2>& route() const { return route_; }
  /// World position of a slot with `offset` in the formation frame (x ahead, y to the left).
  Vec2 slotPosition(Vec2 offset) const;

 private:
  FormationSettings settings_;
  std::vector<Vec2> route_;
  std::size_t next_ = 0;  // index of the route point the centre heads for
  bool done_ = true;
  Vec2 at_, vel_, heading_;
};

/// One member's own state: all it needs besides its position, velocity and slot (so it can
/// travel with the member, e.g. when the member changes zones).
struct MemberState {
  MemberMode mode = MemberMode::InFormation;  ///< what it is doing
  std::vector<std::int32_t> path;             ///< rejoin path: cells as x, y pairs, start first
  std::int32_t at = 0;                        ///< index of the next cell of `path`
  Vec2 planned_for;                           ///< centre position the path was planned to
};

/// Another member as a neighbour: its id (for the order of sums and ties) and position.
struct MemberNeighbour {
  std::uint64_t id = 0;  ///< unique id
  Vec2 pos;              ///< position at the start of the step
};

/// Steps members one at a time against a centre: mode changes, the rejoin A*, steering to
/// the slot, separation from the other members and the move on the map. A member's step reads
/// only its own state, its slot, the centre and its neighbours.
class MemberStepper {
 public:
  /// Steps on `map` (which must outlive the stepper).
  MemberStepper(const ai::GridMap& map, const MapFrame& frame, const FormationSettings& settings);

  /// Steps member `id` with slot `offset`: `pos`/`vel` are read and overwritten. `neighbours`
  /// are the other members (entries with `id` itself are skipped); the separation adds them
  /// in the order given, so pass them in one canonical order (e.g. ascending id).
  void step(std::uint64_t id, MemberState& m, Vec2 offset, const FormationCentre& centre,
            std::span<const MemberNeighbour> neighbours, Vec2& pos, Vec2& vel, double dt);
  /// Number of rejoin paths planned so far (A* calls for members).
  int rejoinPlans() const { return rejoin_plans_; }

 private:
  void updateMode(MemberState& m, Vec2 pos, Vec2 slot, const FormationCentre& centre);
  bool planRejoin(MemberState& m, Vec2 pos, const FormationCentre& centre);
  Vec2 desiredVelocity(MemberState& m, Vec2 pos, Vec2 slot, const FormationCentre& centre) const;
  Vec2 waypoint(const MemberState& m, std::int32_t k) const;
  Vec2 separation(std::uint64_t id, Vec2 pos, std::span<const MemberNeighbour> others) const;

  const ai::GridMap& map_;
  MapFrame frame_;
  FormationSettings settings_;
  ai::GridSearch search_;
  ai::GridPath scratch_;
  int rejoin_plans_ = 0;
};

/// One fixed group on a grid map; members are indexed like the slot offsets (their ids are
/// their indices).
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
  Vec2 centre() const { return centre_.position(); }
  /// Current heading (unit vector).
  Vec2 heading() const { return centre_.heading(); }
  /// World position of slot i now.
  Vec2 slotPosition(int i) const { return centre_.slotPosition(slots_[i]); }
  /// Mode of member i.
  MemberMode mode(int i) const { return members_[i].mode; }
  /// True when the centre has reached the end of its route.
  bool centreArrived() const { return centre_.arrived(); }
  /// Number of rejoin paths planned so far (A* calls for members).
  int rejoinPlans() const { return stepper_.rejoinPlans(); }
  /// Number of members.
  int size() const { return int(slots_.size()); }

 private:
  const ai::GridMap& map_;
  MapFrame frame_;
  std::vector<Vec2> slots_;
  std::vector<MemberState> members_;
  FormationCentre centre_;
  MemberStepper stepper_;
  ai::GridSearch search_;
  ai::GridPath scratch_;
  std::vector<MemberNeighbour> snapshot_;  // positions at the start of the step
};

/// A centre route through `points` on the map: A* from each point to the next, as the exact
/// points at the ends and cell centres between. False when a leg is unreachable.
bool planRoute(ai::GridSearch& search, const MapFrame& frame, std::span<const Vec2> points,
               std::vector<Vec2>& route);

/// The same route on a navigation mesh (map.navigation: navmesh): each leg the funnelled mesh
/// path between the points (ai/navmesh_search.h), straight from corner to corner, with the
/// mesh's clearance from walls. False when a leg is unreachable; throws std::invalid_argument
/// naming the point when one is off the mesh (within its agent radius of a wall).
bool planMeshRoute(ai::NavMeshSearch& search, const MapFrame& frame, std::span<const Vec2> points,
                   std::vector<Vec2>& route);

}  // namespace zonesim::crowd
