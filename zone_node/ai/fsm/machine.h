#pragma once
// Run-time state of one agent's data-driven machine: the current state and how long it has
// lasted. Kept apart from the definition so that thousands of agents share one MachineDef.

#include "zone_node/ai/fsm/machine_def.h"

namespace zonesim::ai {

/// One agent's position in a MachineDef.
struct MachineState {
  int state = 0;         ///< current state index
  int ticksInState = 0;  ///< ticks since the last transition
};

/// Starts an agent in the machine's initial state.
inline MachineState startMachine(const MachineDef& def) {
  return MachineState{def.initial, 0};
}

/// Advances one tick with `inputs` (in def.inputs order); returns true when the state changed.
bool stepMachine(const MachineDef& def, MachineState& m, const double* inputs);

}  // namespace zonesim::ai
