#pragma once
// Run-time state of one agent's data-driven machine: the current leaf state and when each level
// of its chain was entered. Kept apart from the definition so thousands of agents share one
// MachineDef.

#include "ai/fsm/machine_def.h"

namespace zonesim::ai {

/// One agent's position in a MachineDef.
struct MachineState {
  int state = 0;                       ///< current leaf state index
  int tick = 0;                        ///< steps taken
  int enteredAt[kMaxStateDepth] = {};  ///< tick at which each level of the chain was entered
  /// Ticks since the leaf state was entered.
  int ticksInState(const MachineDef& def) const {
    return tick - enteredAt[def.states[std::size_t(state)].depth];
  }
};

/// Starts an agent in the machine's initial leaf state.
inline MachineState startMachine(const MachineDef& def) {
  MachineState m;
  m.state = def.initial;
  return m;
}

/// Advances one tick with `inputs` (in def.inputs order): the transitions of the outermost
/// active state are tried first, then inward; returns true when a transition fired.
bool stepMachine(const MachineDef& def, MachineState& m, const double* inputs);

}  // namespace zonesim::ai
