#pragma once
// The decision-making half of AI agents: per agent type, the behaviour the scene composed it
// with (an interpreted state machine from a file, the hand-coded guard, a decision tree, a
// fuzzy machine; GOAP and travel are in agent_goap.h and agent_navigation.h) turns the agent's
// senses into an action. A decision reads only the agent's own state and its senses; its
// machine state lives in AgentData so it migrates with the agent.

#include <memory>
#include <vector>

#include "zone_node/entity_store.h"
#include "zone_node/systems/agent_senses.h"

namespace zonesim {
struct Scene;
}  // namespace zonesim

namespace zonesim::zone {

/// Loaded behaviours of every agent type of a scene.
class AgentDecisions {
 public:
  /// Loads machine files and builds trees and fuzzy machines; throws SceneError naming the
  /// scene line of a type whose machine does not fit (unknown input, unmapped state), or the
  /// machine file's ParseError.
  explicit AgentDecisions(const Scene& scene);
  ~AgentDecisions();

  /// Decides agent `a`'s action (AgentAction) for this tick from its senses; updates its
  /// machine state or blended outputs. GOAP and travel types answer Travel.
  void decide(AgentData& a, const AgentSenses& senses) const;

 private:
  struct Type;
  std::vector<std::unique_ptr<Type>> types_;
};

}  // namespace zonesim::zone
