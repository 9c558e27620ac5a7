#pragma once
// Goal-oriented agents: each plans once, from the type's initial facts to its goal, the cheapest
// sequence of the scene's actions (ai/goap, A* over world states), then executes it:
// go to the action's place, spend its duration there, apply its effects, next. The plan is kept
// in AgentData, so a migrating agent continues the same plan on its new zone.

#include <memory>
#include <vector>

#include "zone_node/entity_store.h"

namespace zonesim {
struct AgentSettings;
}  // namespace zonesim

namespace zonesim::ai {
class GoapPlanner;
}  // namespace zonesim::ai

namespace zonesim::zone {

/// Planners for the scene's GOAP agent types.
class AgentGoapPlans {
 public:
  /// One planner per GOAP type of `agents` (the scene's, which must outlive this).
  explicit AgentGoapPlans(const AgentSettings& agents);
  ~AgentGoapPlans();

  /// Plans for `a` if it has no plan yet; returns false when its plan is done or impossible
  /// (it then idles), else sets (x, z) to the place of its current action.
  bool target(AgentData& a, double& x, double& z);
  /// The agent stands at its action's place for `dt`: once the duration is spent the action's
  /// effects apply and the plan moves on. Returns true when the action completed.
  bool work(AgentData& a, double dt);

 private:
  const AgentSettings& agents_;
  std::vector<std::unique_ptr<ai::GoapPlanner>> planners_;  // by type; null for other types
};

}  // namespace zonesim::zone
