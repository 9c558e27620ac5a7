#pragma once
// AI agents in the zone tick. Each agent type of the scene composes a decision behaviour
// (agent_decisions.h, agent_goap.h), perception (agent_senses.h), needs (health and energy that
// the senses report back) and locomotion (steering, or paths and splines: agent_navigation.h).
// Per tick: agents follow the doors the zone opened or closed, every agent senses the tick's
// starting state, decides, names where it is heading, the path service plans within its budget,
// then every agent moves. An agent's result depends only on its own state (AgentData, which
// migrates with it), the entities within its sight (the halo covers them) and the tick: the same on
// any decomposition provided every zone shares path request keys through the step's gather (the
// budget is the cluster's).

#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "ai/grid_map.h"
#include "common/scene_agents.h"
#include "crowd/lod.h"
#include "crowd/map_frame.h"
#include "crowd/vec2.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"
#include "zone_node/systems/agent_navigation.h"
#include "zone_node/systems/agent_senses.h"
#include "zone_node/systems/step_context.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

class GhostStore;
class AgentDecisions;
class AgentGoapPlans;

/// A chaser on a map re-plans once its quarry is this far (m) from the end of its path.
inline constexpr double kPursuitReplanDistance = 2.0;

/// Agent figures of one tick.
struct AgentTickStats {
  std::uint64_t agents = 0;       ///< agents stepped
  std::uint64_t decisions = 0;    ///< agents that sensed and decided (all, unless time-sliced)
  std::uint64_t transitions = 0;  ///< state machine transitions
  AgentPathStats paths;           ///< path service
};

/// Steps every AI agent of a zone.
class AgentSystem : public ZoneSystem {
 public:
  /// Loads the scene's behaviours (throws SceneError or ai::ParseError naming the file and
  /// line); `map` is the zone's map (doors applied by the zone) or null.
  AgentSystem(const Scene& scene, ZoneMap* map);
  ~AgentSystem();

  /// Whether the scene has agent types at all.
  bool active() const override;
  /// Widest sight of a type: agents read ghosts this far across a border.
  double reach() const { return reach_; }
  /// Advances every agent by one tick; collective through ctx.cluster.gather (the zones share
  /// their path request keys) when the scene has a map. Adds the agent counters.
  void step(StepContext& ctx) override;
  /// Ghosts carry the agent type, so that it sees only who is a foe across a border.
  std::vector<GhostColumn> ghostColumns() const override { return {agentTypeColumn()}; }
  /// What the last step did.
  const AgentTickStats& lastStats() const { return last_; }

 private:
  /// Ticks between an agent's decisions: agents.decide_every, or longer in the scene's lod
  /// bands (far from every player).
  int decisionPeriod(const Vec3& pos, std::span<const crowd::Vec2> players) const;
  /// Fills decides_ for this tick (left empty when every agent decides every tick).
  void planDecisions(const EntityStore& store, std::span<const crowd::Vec2> players,
                     std::uint64_t tick);
  void move(EntityStore& store, std::size_t i, const AgentSenses& senses, double dt);
  bool pursues(const AgentData& a, const AgentType& t, const AgentSenses& s) const;
  void pursue(EntityStore& store, std::size_t i, const AgentSenses& s, std::int64_t tick);
  void updateNeeds(AgentData& a, const AgentType& t, const AgentSenses& s, double speed,
                   double dt) const;

  const Scene& scene_;
  double reach_ = 0;
  std::unique_ptr<AgentDecisions> decisions_;
  std::unique_ptr<AgentGoapPlans> goap_;
  AgentNavigation nav_;
  std::vector<AgentSenses> senses_;
  crowd::LodSettings lod_;             // the scene's lod bands (used when it has the key)
  std::vector<std::uint8_t> decides_;  // per store index this tick; empty: everyone decides
  AgentTickStats last_;
};

}  // namespace zonesim::zone
