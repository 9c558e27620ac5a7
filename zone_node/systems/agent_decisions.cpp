#include "zone_node/systems/agent_decisions.h"

#include <algorithm>
#include <string>

#include "ai/decision/decision_tree.h"
#include "ai/decision/fuzzy_machine.h"
#include "ai/fsm/guard_machine.h"
#include "ai/fsm/machine.h"
#include "ai/fsm/machine_def.h"
#include "common/scene.h"

namespace zonesim::zone {

namespace {

[[noreturn]] void typeError(const AgentType& t, const std::string& what) {
  throw SceneError(t.file + ":" + std::to_string(t.line) + ": agents.types." + t.name + ": " +
                   what);
}

// The guard's states in GuardMachine::State order and what each does.
constexpr AgentAction kGuardActions[] = {AgentAction::Wander, AgentAction::Chase,
                                         AgentAction::Attack, AgentAction::Flee};

}  // namespace

struct AgentDecisions::Type {
  AgentType::Behaviour behaviour;
  double speed = 1;
  ai::MachineDef machine;
  std::vector<int> input_sense;   // machine input -> AgentSense
  std::vector<int> state_action;  // machine state -> AgentAction (-1: composite)
  ai::DecisionTree tree;
  std::unique_ptr<ai::FuzzyMachine> fuzzy;
};

AgentDecisions::AgentDecisions(const Scene& scene) {
  for (const AgentType& t : scene.agents.types) {
    auto type = std::make_unique<Type>();
    type->behaviour = t.behaviour;
    type->speed = t.speed;
    switch (t.behaviour) {
      case AgentType::Behaviour::Fsm: {
        type->machine = ai::loadMachineYaml(t.machine);  // ParseError: machine file:line
        const ai::MachineDef& def = type->machine;
        for (const std::string& input : def.inputs) {
          const auto* end = std::end(kAgentSenseNames);
          const auto* it = std::find(std::begin(kAgentSenseNames), end, input);
          if (it == end)
            typeError(t, "machine " + t.machine + " reads input '" + input +
                             "', which agents do not sense");
          type->input_sense.push_back(int(it - std::begin(kAgentSenseNames)));
        }
        type->state_action.assign(def.states.size(), -1);
        for (const auto& [state, action] : t.state_actions) {
          int s = def.stateIndex(state);
          if (s < 0)
            typeError(t, "actions: machine " + t.machine + " has no state '" + state + "'");
          if (def.states[std::size_t(s)].initial_child >= 0)
            typeError(t, "actions: state '" + state + "' has substates; map its leaves");
          type->state_action[std::size_t(s)] = action;
        }
        for (std::size_t s = 0; s < def.states.size(); ++s)
          if (def.states[s].initial_child < 0 && type->state_action[s] < 0)
            typeError(t, "actions: state '" + def.states[s].name + "' has no action");
        break;
      }
      case AgentType::Behaviour::Tree: {
        // Scene nodes come root first with children after their parent: build from the back.
        std::vector<int> built(t.tree.size(), -1);
        for (std::size_t k = t.tree.size(); k-- > 0;) {
          const AgentTreeNode& n = t.tree[k];
          built[k] = n.sense < 0
                         ? type->tree.addLeaf(n.action)
                         : type->tree.addTest(n.sense, n.threshold, built[std::size_t(n.if_less)],
                                              built[std::size_t(n.otherwise)]);
        }
        type->tree.setRoot(built[0]);
        break;
      }
      case AgentType::Behaviour::Fuzzy:
        type->fuzzy = std::make_unique<ai::FuzzyMachine>(2);
        for (const AgentFuzzyState& f : t.fuzzy)
          type->fuzzy->addState(f.sense, {f.a, f.b, f.c, f.d}, {f.speed, f.approach});
        break;
      case AgentType::Behaviour::Guard:
      case AgentType::Behaviour::Goap:
      case AgentType::Behaviour::Travel:
        break;
    }
    types_.push_back(std::move(type));
  }
}

AgentDecisions::~AgentDecisions() = default;

void AgentDecisions::decide(AgentData& a, const AgentSenses& senses) const {
  const Type& t = *types_[std::size_t(a.type)];
  const double* in = senses.value;
  switch (t.behaviour) {
    case AgentType::Behaviour::Fsm: {
      double inputs[32];
      for (std::size_t k = 0; k < t.input_sense.size() && k < 32; ++k)
        inputs[k] = in[t.input_sense[k]];
      ai::MachineState m;
      m.state = a.state;
      m.tick = a.step;
      std::copy(std::begin(a.entered), std::end(a.entered), m.enteredAt);
      if (ai::stepMachine(t.machine, m, inputs)) ++a.transitions;
      a.state = m.state;
      a.step = m.tick;
      std::copy(std::begin(m.enteredAt), std::end(m.enteredAt), a.entered);
      a.action = t.state_action[std::size_t(a.state)];
      return;
    }
    case AgentType::Behaviour::Guard: {
      ai::GuardMachine g(ai::GuardMachine::State(a.state), a.entered[0]);
      if (g.step({in[int(AgentSense::EnemyDistance)], in[int(AgentSense::Health)]}))
        ++a.transitions;
      a.state = int(g.state());
      a.entered[0] = g.ticksInState();
      ++a.step;
      a.action = int(kGuardActions[a.state]);
      return;
    }
    case AgentType::Behaviour::Tree:
      a.action = t.tree.decide(in);
      return;
    case AgentType::Behaviour::Fuzzy: {
      thread_local std::vector<double> memberships, out;
      t.fuzzy->evaluate(in, memberships, out);
      a.speed_factor = std::clamp(out[0] / t.speed, 0.0, 1.0);
      a.approach = senses.enemy_seen ? out[1] : 0.0;
      a.action = int(a.approach >= 0 ? AgentAction::Chase : AgentAction::Flee);
      if (!senses.enemy_seen) a.action = int(AgentAction::Wander);
      return;
    }
    case AgentType::Behaviour::Goap:
    case AgentType::Behaviour::Travel:
      a.action = int(AgentAction::Travel);
      return;
  }
}

}  // namespace zonesim::zone
