#pragma once
// How AI agents get somewhere: on a scene with an obstacle map, navigating types ask the zone's
// PathService for an A* or HPA* path and walk it along a centripetal Catmull-Rom spline from their
// exact position to their exact target (with `map.navigation: navmesh`, a navigation-mesh path
// between those exact points, walked straight from corner to corner); doors that close at a scene
// time cut paths, and the agents whose remaining path crossed the door ask again from where they
// stand. Without a map, or for types that do not navigate, they steer straight at the target. The
// path itself is AgentData (it migrates with the agent); the spline is a local cache rebuilt from
// it, so it is the same on every rank.
//
// The per-tick budget is the cluster's, not the zone's: a waiting request is keyed by (tick it was
// asked, agent id), both in AgentData, so it migrates with its agent. Each tick every zone sends
// the keys of its oldest `paths_per_tick` requests to all (ClusterGather), every zone sorts the
// union the same way and plans those of its own agents among the first `paths_per_tick`. With an
// expansion budget the zones then share what each of those plans expanded and all cut the list
// at the same place (the first request whose predecessors expanded the budget), so which request
// is served in which tick does not depend on the decomposition.

#include <cstdint>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

#include "ai/grid_map.h"
#include "ai/path_service.h"
#include "ai/spline_path.h"
#include "common/math.h"
#include "crowd/map_frame.h"
#include "zone_node/entity_store.h"
#include "zone_node/systems/step_context.h"
#include "zone_node/zone_map.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// AgentData::nav values.
enum class AgentNav : std::int32_t { None = 0, Waiting = 1, Moving = 2, Arrived = 3, NoPath = 4 };

/// Path-service figures of one tick.
struct AgentPathStats {
  std::uint64_t planned = 0;  ///< requests served this tick (planned or from the cache)
  std::uint64_t queued = 0;   ///< requests still waiting after the tick
  std::uint64_t replans = 0;  ///< agents whose path a door cut this tick
  std::uint64_t plan_ns = 0;  ///< time in the planner this tick (agents.paths.audit left out)
  /// With agents.paths.audit: plans compared with the A* optimum this tick, the sum of their
  /// overheads in millionths, and the largest overhead of the run so far in millionths.
  std::uint64_t audited = 0;
  std::uint64_t overhead_ppm = 0;
  std::uint64_t overhead_max_ppm = 0;
  std::uint64_t audit_ns = 0;  ///< time the audit's A* searches took this tick
};

/// Paths, doors and path following for a zone's agents.
class AgentNavigation {
 public:
  /// `map` (the zone's, which the doors change) may be null for a scene without a map.
  AgentNavigation(const Scene& scene, ZoneMap* map);
  ~AgentNavigation();

  /// Whether the scene has a map to plan on.
  bool hasMap() const { return service_ != nullptr; }
  /// The map as the doors left it (null without a map).
  const ai::GridMap* grid() const { return map_ ? &map_->world().grid : nullptr; }
  /// Where the map lies.
  const crowd::MapFrame& frame() const { return frame_; }

  /// Follows the doors the zone applied this tick (ZoneMap::doorsNow): agents whose path
  /// crosses a closed door, and agents without a path when one opens, will ask again.
  void followDoors(EntityStore& store);
  /// Agent i heads for (x, z) in tick `tick`: a navigating agent without a path to it asks for
  /// one.
  void want(EntityStore& store, std::size_t i, double x, double z, bool navigate,
            std::int64_t tick);
  /// Serves the waiting requests that fall within the cluster's budget this tick (collective
  /// through `gather`, which shares the zones' request keys; empty: a lone zone) and hands
  /// their paths to their agents.
  void plan(EntityStore& store, const ClusterGather& gather);
  /// Moves agent i toward its target by `dt` at `speed`: along its spline when it has a path,
  /// else straight with braking (the caller's steering integrates `desired`). Returns true
  /// when the position was set directly (spline), false when `desired` holds a velocity.
  bool follow(EntityStore& store, std::size_t i, double speed, double accel, double arrive,
              double dt, Vec3& desired);
  /// Where an agent at (x, z) fleeing a threat at (ex, ez) should run: of the points up to
  /// `radius` away in 16 directions that it sees in a straight line (no wall between), the one
  /// farthest from the threat (lowest direction on a tie), as the centre of its cell; reachable
  /// by construction. The agent's own cell when walls surround it.
  crowd::Vec2 fleeTarget(double x, double z, double ex, double ez, double radius) const;
  /// Figures since the last call.
  AgentPathStats takeStats();

 private:
  ai::Cell startCell(double x, double z) const;
  ai::Vec2 meshStart(ai::Vec2 p) const;  // p, or the nearest cell centre on the mesh
  ai::Vec2 toMap(double x, double z) const;                       // world -> map units
  crowd::Vec2 cornerOf(std::int32_t x, std::int32_t y) const;     // lattice point -> world
  bool meshPathTouches(const AgentData& a, ai::Cell cell) const;  // a navmesh path's segments
  const ai::SplinePath& splineOf(const EntityStore& store, std::size_t i);

  const Scene& scene_;
  ZoneMap* map_ = nullptr;
  crowd::MapFrame frame_;
  std::unique_ptr<ai::PathService> service_;
  bool navmesh_ = false;  // AgentData::path holds mesh corners between its end cells
  std::uint64_t map_changes_ = 0;
  struct Waiting {
    std::uint64_t asked, id;  // the request's key
    std::size_t index;        // in the store
    int expanded = -1;        // nodes its plan expanded this tick; -1: not planned
    bool found = false;
    ai::GridPath path;
  };
  std::vector<Waiting> waiting_;  // this zone's requests, oldest first
  std::uint64_t served_ = 0;
  struct Spline {
    std::vector<std::int32_t> path;
    double ox = 0, oz = 0, tx = 0, tz = 0;
    std::unique_ptr<ai::SplinePath> spline;
  };
  std::unordered_map<std::uint64_t, Spline> splines_;  // looked up by agent id, never iterated
  std::uint64_t replans_ = 0;
  ai::PathServiceStats seen_;  // the service's counters at the last takeStats()
};

}  // namespace zonesim::zone
