#pragma once
// The phases of a zone tick, in order (DESIGN.md), and the per-tick figures the metrics report.

#include <array>
#include <cstdint>

#include "common/timer.h"

namespace zonesim::zone {

enum class Phase { Input, Ai, Avatars, Physics, Gpu, Migrate, Halo, Publish, Checks, Count };
constexpr std::size_t kPhaseCount = std::size_t(Phase::Count);
constexpr std::array<const char*, kPhaseCount> kPhaseNames = {
    "input", "ai", "avatars", "physics", "gpu", "migrate", "halo", "publish", "checks"};

/// Named steps inside the phases, as Box2D's b2Profile names its stages: the metrics write each
/// as `<phase>.<step>_ms`, so a slow phase shows which system or stage grew.
enum class Stage {
  AiDoors,
  AiNeighbours,
  AiLod,
  AiInteractions,
  AiAgents,
  AiWander,
  AiFlock,
  AiFlow,
  AiFormations,
  AiRoads,
  AiAnts,
  AiAdaptation,
  PhysicsIntegrate,
  PhysicsBroadphase,
  PhysicsNarrowphase,
  PhysicsPrepare,
  PhysicsSolve,
  PhysicsIslands,
  PhysicsBorder,
  MigrateMail,
  Count
};
constexpr std::size_t kStageCount = std::size_t(Stage::Count);
constexpr std::array<const char*, kStageCount> kStageNames = {"ai.doors",
                                                              "ai.neighbours",
                                                              "ai.lod",
                                                              "ai.interactions",
                                                              "ai.agents",
                                                              "ai.wander",
                                                              "ai.flock",
                                                              "ai.flow",
                                                              "ai.formations",
                                                              "ai.roads",
                                                              "ai.ants",
                                                              "ai.adaptation",
                                                              "physics.integrate",
                                                              "physics.broadphase",
                                                              "physics.narrowphase",
                                                              "physics.prepare",
                                                              "physics.solve",
                                                              "physics.islands",
                                                              "physics.border",
                                                              "migrate.mail"};

/// Seconds per phase of one tick, and per named step inside them.
struct TickProfile : PhaseProfile<Phase, kPhaseCount> {
  std::array<double, kStageCount> stage_seconds{};
  using PhaseProfile::operator[];
  double& operator[](Stage s) { return stage_seconds[std::size_t(s)]; }
  double operator[](Stage s) const { return stage_seconds[std::size_t(s)]; }
};

/// Counters of one tick (reset at the start of each tick).
struct TickCounters {
  std::uint64_t migrated_out = 0;
  std::uint64_t migrated_in = 0;
  std::uint64_t handoffs_out = 0;
  std::uint64_t handoffs_in = 0;
  std::uint64_t inputs_applied = 0;
  std::uint64_t inputs_duplicate = 0;
  std::uint64_t inputs_forwarded = 0;
  std::uint64_t inputs_unroutable = 0;
  std::uint64_t inputs_skipped = 0;  ///< sequence numbers that never arrived (gaps given up on)
  std::uint64_t inputs_held = 0;     ///< arrived ahead of a missing number: held to apply in order
  std::uint64_t avatars_spawned = 0;
  std::uint64_t avatars_refused = 0;  ///< spawn requests of a player kind the scene lacks
  std::uint64_t avatars_orphaned = 0;  ///< removed after the orphan grace without an input
  /// Despawn requests ignored: from a session the player left by resuming elsewhere (counted
  /// by the zone holding the avatar).
  std::uint64_t despawns_superseded = 0;
  std::uint64_t entities_destroyed = 0;
  std::uint64_t rebalances = 0;
  std::uint64_t dds_write_failures = 0;
  std::uint64_t imbalance_permille = 0;  ///< max/mean cost at the last balance check, x1000
  std::uint64_t migration_bytes = 0;
  std::uint64_t bodies_awake = 0;
  std::uint64_t bodies_held = 0;  ///< awake bodies far from players waiting for their step (lod)
  std::uint64_t particles_alive = 0;
  std::uint64_t published_updates = 0;
  std::uint64_t published_enters = 0;
  std::uint64_t published_leaves = 0;
  std::uint64_t published_cells = 0;
  std::uint64_t published_keyframes = 0;
  std::uint64_t subscribed_cells = 0;
  std::uint64_t published_states = 0;   ///< entity states computed for subscribed cells
  std::uint64_t published_histories = 0;  ///< motion histories kept: read cells and next to them
  std::uint64_t ghosts = 0;             ///< neighbours' entities held as ghosts after the refresh
  std::uint64_t ghosts_sent = 0;        ///< entity copies sent to neighbours
  std::uint64_t halo_bytes = 0;         ///< bytes of those copies
  std::uint64_t halo_rebuilds = 0;      ///< 1 when the ghost send lists were rebuilt
  std::uint64_t island_bodies_in = 0;   ///< other zones' bodies this zone solved in its islands
  std::uint64_t island_bodies_out = 0;  ///< this zone's bodies solved in other zones' islands
  std::uint64_t island_exchanges = 0;   ///< 1 when islands were found and bodies traded
  std::uint64_t physics_steps = 0;      ///< engine world steps (0 while every body sleeps)
  /// Body rows the physics stage read (0 while every body sleeps and nothing can wake one)
  std::uint64_t bodies_checked = 0;
  std::uint64_t agents = 0;             ///< AI agents stepped
  std::uint64_t flow_npcs_visited = 0;  ///< flow-field NPCs gathered (0 while their crowds sleep)
  std::uint64_t agent_transitions = 0;  ///< their state machine transitions
  std::uint64_t agent_decisions = 0;    ///< agents that sensed and decided (agents.decide_every)
  std::uint64_t paths_planned = 0;      ///< path planner calls (at most the per-tick budget)
  std::uint64_t paths_queued = 0;       ///< path requests left waiting for a later tick
  std::uint64_t path_replans = 0;       ///< agents whose path a closing door cut
  std::uint64_t path_plan_ns = 0;       ///< time in the path planner (audits left out)
  /// agents.paths.audit: plans compared with the A* optimum, their overheads summed (in
  /// millionths), and the largest overhead so far (millionths; a gauge: the run's is its last)
  std::uint64_t paths_audited = 0;
  std::uint64_t path_overhead_ppm = 0;
  std::uint64_t path_overhead_max_ppm = 0;
  std::uint64_t path_audit_ns = 0;      ///< time in the audit's A* searches (inside the ai phase)
  std::uint64_t quarantined = 0;        ///< entities frozen for a non-finite state (quarantine.h)
  // Messages between entities (cluster/entity_mail.h) and what the interactions made of them.
  std::uint64_t mail_posted = 0;      ///< messages and replies posted on this rank
  std::uint64_t mail_applied = 0;     ///< applied to this rank's entities
  std::uint64_t mail_cross_zone = 0;  ///< of those, posted on another rank
  std::uint64_t mail_forwarded = 0;   ///< passed on after their target migrated away
  std::uint64_t mail_refused = 0;     ///< target gone
  std::uint64_t mail_bytes = 0;
  std::uint64_t hits = 0;             ///< hits this rank's entities took
  std::uint64_t kills = 0;            ///< of those, killing ones (confirmed to the hitter)
  std::uint64_t gifts = 0;            ///< items this rank's avatars received
  std::uint64_t gifts_returned = 0;   ///< gifts given back to their giver (recipient gone)
  std::uint64_t pickups = 0;          ///< items taken, as their owner granted them
  std::uint64_t pickups_contested = 0;  ///< of those, claimed by more than one in the tick
  std::uint64_t pickups_denied = 0;     ///< claims that lost (nearer claimant, or item gone)
  std::uint64_t items_removed = 0;      ///< taken items that left the world (decision checkpointed)
};

/// Every counter with its name: totals, metrics lines and summaries iterate this one list.
struct CounterField {
  const char* name;
  std::uint64_t TickCounters::*field;
  bool gauge;  ///< a level (last value matters), not an event count (the sum matters)
};
inline constexpr CounterField kCounterFields[] = {
    {"migrated_out", &TickCounters::migrated_out, false},
    {"migrated_in", &TickCounters::migrated_in, false},
    {"handoffs_out", &TickCounters::handoffs_out, false},
    {"handoffs_in", &TickCounters::handoffs_in, false},
    {"inputs_applied", &TickCounters::inputs_applied, false},
    {"inputs_duplicate", &TickCounters::inputs_duplicate, false},
    {"inputs_forwarded", &TickCounters::inputs_forwarded, false},
    {"inputs_unroutable", &TickCounters::inputs_unroutable, false},
    {"inputs_skipped", &TickCounters::inputs_skipped, false},
    {"inputs_held", &TickCounters::inputs_held, false},
    {"avatars_spawned", &TickCounters::avatars_spawned, false},
    {"avatars_refused", &TickCounters::avatars_refused, false},
    {"avatars_orphaned", &TickCounters::avatars_orphaned, false},
    {"despawns_superseded", &TickCounters::despawns_superseded, false},
    {"entities_destroyed", &TickCounters::entities_destroyed, false},
    {"rebalances", &TickCounters::rebalances, false},
    {"dds_write_failures", &TickCounters::dds_write_failures, false},
    {"imbalance_permille", &TickCounters::imbalance_permille, true},
    {"migration_bytes", &TickCounters::migration_bytes, false},
    {"bodies_awake", &TickCounters::bodies_awake, true},
    {"bodies_held", &TickCounters::bodies_held, true},
    {"particles_alive", &TickCounters::particles_alive, true},
    {"published_updates", &TickCounters::published_updates, false},
    {"published_enters", &TickCounters::published_enters, false},
    {"published_leaves", &TickCounters::published_leaves, false},
    {"published_cells", &TickCounters::published_cells, false},
    {"published_keyframes", &TickCounters::published_keyframes, false},
    {"subscribed_cells", &TickCounters::subscribed_cells, true},
    {"published_states", &TickCounters::published_states, false},
    {"published_histories", &TickCounters::published_histories, false},
    {"ghosts", &TickCounters::ghosts, true},
    {"ghosts_sent", &TickCounters::ghosts_sent, false},
    {"halo_bytes", &TickCounters::halo_bytes, false},
    {"halo_rebuilds", &TickCounters::halo_rebuilds, false},
    {"island_bodies_in", &TickCounters::island_bodies_in, false},
    {"island_bodies_out", &TickCounters::island_bodies_out, false},
    {"island_exchanges", &TickCounters::island_exchanges, false},
    {"physics_steps", &TickCounters::physics_steps, false},
    {"bodies_checked", &TickCounters::bodies_checked, false},
    {"agents", &TickCounters::agents, true},
    {"flow_npcs_visited", &TickCounters::flow_npcs_visited, false},
    {"agent_transitions", &TickCounters::agent_transitions, false},
    {"agent_decisions", &TickCounters::agent_decisions, false},
    {"paths_planned", &TickCounters::paths_planned, false},
    {"paths_queued", &TickCounters::paths_queued, true},
    {"path_replans", &TickCounters::path_replans, false},
    {"path_plan_ns", &TickCounters::path_plan_ns, false},
    {"paths_audited", &TickCounters::paths_audited, false},
    {"path_overhead_ppm", &TickCounters::path_overhead_ppm, false},
    {"path_overhead_max_ppm", &TickCounters::path_overhead_max_ppm, true},
    {"path_audit_ns", &TickCounters::path_audit_ns, false},
    {"quarantined", &TickCounters::quarantined, false},
    {"mail_posted", &TickCounters::mail_posted, false},
    {"mail_applied", &TickCounters::mail_applied, false},
    {"mail_cross_zone", &TickCounters::mail_cross_zone, false},
    {"mail_forwarded", &TickCounters::mail_forwarded, false},
    {"mail_refused", &TickCounters::mail_refused, false},
    {"mail_bytes", &TickCounters::mail_bytes, false},
    {"hits", &TickCounters::hits, false},
    {"kills", &TickCounters::kills, false},
    {"gifts", &TickCounters::gifts, false},
    {"gifts_returned", &TickCounters::gifts_returned, false},
    {"pickups", &TickCounters::pickups, false},
    {"pickups_contested", &TickCounters::pickups_contested, false},
    {"pickups_denied", &TickCounters::pickups_denied, false},
    {"items_removed", &TickCounters::items_removed, false}};

}  // namespace zonesim::zone
