#pragma once
// What AI agents perceive: the nearest enemy (a player's avatar, or an NPC that is not an AI
// agent) within the type's sight, over this zone's entities and the neighbours' ghosts alike,
// plus the agent's own needs and progress. Sight may not exceed the halo width (the scene
// loader checks), so an enemy within sight is always known to the agent's zone, whichever zone
// owns it; ties go to the lower id. All agents sense the tick's starting state.

#include <cstdint>
#include <span>
#include <vector>

#include "common/math.h"
#include "common/scene_agents.h"
#include "zone_node/entity_store.h"

namespace zonesim::zone {

class GhostStore;

/// Distance reported when no enemy is within sight.
inline constexpr double kNoEnemy = 1e9;

/// One agent's perception this tick.
struct AgentSenses {
  double value[int(AgentSense::Count)] = {};  ///< in AgentSense order
  Vec3 enemy = Vec3::Zero();                  ///< nearest enemy's position when one is seen
  bool enemy_seen = false;                    ///< an enemy is within sight
};

/// Fills `out[i]` for every agent i of the store (others are left default) at time `time`.
/// Agents with decides[i] set look now; the others (time-sliced, agents.decide_every) get what
/// they saw when they last decided (AgentData's enemy_* fields), with their needs and progress
/// as they are now. An empty `decides`: every agent looks.
void senseAgents(const AgentSettings& settings, const EntityStore& store, const GhostStore* ghosts,
                 double time, std::span<const std::uint8_t> decides, std::vector<AgentSenses>& out);

}  // namespace zonesim::zone
