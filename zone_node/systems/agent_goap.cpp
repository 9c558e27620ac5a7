#include "zone_node/systems/agent_goap.h"

#include "ai/goap/goap_planner.h"
#include "common/scene_agents.h"

namespace zonesim::zone {

AgentGoapPlans::AgentGoapPlans(const AgentSettings& agents) : agents_(agents) {
  for (const AgentType& t : agents.types) {
    std::unique_ptr<ai::GoapPlanner> p;
    if (t.behaviour == AgentType::Behaviour::Goap) {
      p = std::make_unique<ai::GoapPlanner>();
      for (const std::string& f : t.goap.facts) p->addFact(f);
      for (const AgentGoapAction& a : t.goap.actions)
        p->addAction(
            {a.name, {a.pre_mask, a.pre_values}, {a.effect_mask, a.effect_values}, a.cost});
    }
    planners_.push_back(std::move(p));
  }
}

AgentGoapPlans::~AgentGoapPlans() = default;

bool AgentGoapPlans::target(AgentData& a, double& x, double& z) {
  const AgentGoap& g = agents_.types[std::size_t(a.type)].goap;
  if (a.plan_length < 0) {
    std::vector<int> plan;
    bool found = planners_[std::size_t(a.type)]->plan(a.facts, {g.goal_mask, g.goal_values}, plan);
    a.plan_length = 0;
    if (found && plan.size() <= std::size_t(AgentData::kMaxPlan)) {
      for (std::size_t k = 0; k < plan.size(); ++k) a.plan[k] = plan[k];
      a.plan_length = std::int32_t(plan.size());
    }
    a.plan_step = 0;
    a.action_time = 0;
  }
  if (a.plan_step >= a.plan_length) return false;
  const AgentGoapAction& act = g.actions[std::size_t(a.plan[a.plan_step])];
  x = act.x;
  z = act.z;
  return true;
}

bool AgentGoapPlans::work(AgentData& a, double dt) {
  const AgentGoap& g = agents_.types[std::size_t(a.type)].goap;
  const AgentGoapAction& act = g.actions[std::size_t(a.plan[a.plan_step])];
  a.action_time += dt;
  if (a.action_time < act.duration_s) return false;
  a.facts = (a.facts & ~act.effect_mask) | (act.effect_values & act.effect_mask);
  a.plan_cost += act.cost;
  ++a.plan_step;
  a.action_time = 0;
  return true;
}

}  // namespace zonesim::zone
