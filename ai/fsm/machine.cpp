#include "ai/fsm/machine.h"

#include <algorithm>

namespace zonesim::ai {

bool stepMachine(const MachineDef& def, MachineState& m, const double* inputs) {
  // The active chain from the top level down to the leaf.
  int chain[kMaxStateDepth];
  const int leafDepth = def.states[std::size_t(m.state)].depth;
  for (int s = m.state; s >= 0; s = def.states[std::size_t(s)].parent) {
    chain[def.states[std::size_t(s)].depth] = s;
  }
  for (int level = 0; level <= leafDepth; ++level) {
    const int elapsed = m.tick - m.enteredAt[level];
    for (const TransitionDef& t : def.states[std::size_t(chain[level])].transitions) {
      if (elapsed < t.min_ticks) continue;
      bool all = true;
      for (const Condition& c : t.conditions) all = all && holds(c, inputs);
      if (!all) continue;
      // Levels above the transition's owner that the new chain shares stay entered; the
      // owner's level and everything below are left and (re-)entered now.
      const int leaf = def.enterLeaf(t.to);
      const int newDepth = def.states[std::size_t(leaf)].depth;
      int keep = 0;
      for (int s = leaf; s >= 0; s = def.states[std::size_t(s)].parent) {
        int d = def.states[std::size_t(s)].depth;
        if (d < level && s == chain[d]) keep = std::max(keep, d + 1);
      }
      for (int d = keep; d <= newDepth; ++d) m.enteredAt[d] = m.tick + 1;
      m.state = leaf;
      ++m.tick;
      return true;
    }
  }
  ++m.tick;
  return false;
}

}  // namespace zonesim::ai
