#include "zone_node/ai/fsm/machine.h"

namespace zonesim::ai {

bool stepMachine(const MachineDef& def, MachineState& m, const double* inputs) {
  for (const TransitionDef& t : def.states[std::size_t(m.state)].transitions) {
    if (m.ticksInState < t.minTicks) continue;
    bool all = true;
    for (const Condition& c : t.conditions) all = all && holds(c, inputs);
    if (!all) continue;
    m.state = t.to;
    m.ticksInState = 0;
    return true;
  }
  ++m.ticksInState;
  return false;
}

}  // namespace zonesim::ai
