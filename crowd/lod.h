#pragma once
// Level of detail for crowd updates: agents near any player are updated every tick with full
// steering; farther ones every Nth tick with N times the step (catching up the time they
// skipped), and the farthest optionally without steering (they ride their field or path and
// skip the neighbour query). Updates of one level are spread over the N ticks by a hash of
// the id, so the cost per tick stays flat, and the schedule depends only on ids, positions and
// the tick: every rank computes the same plan for the same agent.

#include <cstdint>
#include <span>
#include <vector>

#include "crowd/step_plan.h"
#include "crowd/vec2.h"

namespace zonesim::crowd {

/// LOD radii and update periods (scene settings).
struct LodSettings {
  double near_radius = 40.0;  ///< within this distance of a player: every tick, full steering
  double far_radius = 120.0;  ///< from near_radius to here: every mid_every ticks
  int mid_every = 2;          ///< update period of the middle band (ticks)
  int far_every = 8;          ///< update period beyond far_radius (ticks)
  bool mid_steers = true;     ///< middle band keeps full steering
  bool far_steers = false;    ///< far band: path/field following only, no neighbour query
  /// An agent whose cell (a world-aligned square of crowded_cell m) holds at least this many
  /// agents, itself included, updates every tick with full steering wherever it is: in a dense
  /// queue far agents riding their field would pass through each other and arrive early.
  /// 0: off.
  int crowded_count = 0;
  double crowded_cell = 4.0;  ///< m, side of the crowding cells
};

/// Detail level of an agent.
enum class LodLevel : std::uint8_t { Near = 0, Mid = 1, Far = 2 };

/// The level of an agent at `pos`: its distance to the nearest player against the radii (Far
/// when there are no players).
LodLevel lodLevel(Vec2 pos, std::span<const Vec2> players, const LodSettings& settings);

/// Ticks between an agent's updates at `level`.
int lodPeriod(LodLevel level, const LodSettings& settings);

/// Whether the agent with `id` updates at `tick` when it updates every `every` ticks: one tick
/// in `every`, picked by a hash of the id, so the agents spread over the ticks and every rank
/// plans the same.
bool lodDue(std::uint64_t id, std::int64_t tick, int every);

/// Per agent in `agents`, how many agents lie in its cell of a world-aligned square grid of
/// side `cell` m: those of `agents` whose `counted` is non-zero (all when `counted` is empty)
/// and all of `others` (ghosts), written to `out`. An agent not counted still gets its cell's
/// count.
void crowdingCounts(std::span<const Vec2> agents, std::span<const std::uint8_t> counted,
                    std::span<const Vec2> others, double cell, std::vector<std::uint32_t>& out);

/// Builds StepPlans for a set of agents each tick.
class LevelOfDetail {
 public:
  /// A planner with the given radii and periods.
  explicit LevelOfDetail(const LodSettings& settings);

  /// Plans tick `tick` (step length `dt`) for agents at `pos` with `ids`, given the players'
  /// positions. `last_tick`: per agent, the tick of its last update (read and written; the
  /// caller keeps it with the agent, -1 for new agents); when empty, an update advances by
  /// its period times dt, which loses or gains time only when an agent changes level.
  /// `crowding`: per agent, its cell's count (crowdingCounts); when given and the settings'
  /// crowded_count is set, agents in crowded cells are planned as near.
  StepPlan plan(std::span<const std::uint64_t> ids, std::span<const Vec2> pos,
                std::span<const Vec2> players, std::int64_t tick, double dt,
                std::span<std::int64_t> last_tick = {},
                std::span<const std::uint32_t> crowding = {});

  /// Level of agent i in the last plan.
  LodLevel level(std::size_t i) const { return LodLevel(level_[i]); }
  /// Agents per level in the last plan.
  const std::size_t* levelCounts() const { return counts_; }
  /// Agents updated in the last plan.
  std::size_t updated() const { return updated_; }
  /// The settings in use.
  const LodSettings& settings() const { return settings_; }

 private:
  LodSettings settings_;
  std::vector<double> dt_;
  std::vector<std::uint8_t> steer_;
  std::vector<std::uint8_t> level_;
  std::size_t counts_[3] = {0, 0, 0};
  std::size_t updated_ = 0;
};

}  // namespace zonesim::crowd
