#include "ai/adapt/npc_params.h"

namespace zonesim::ai::adapt {

NpcParams paramsForDifficulty(double d, const NpcRanges& r) {
  auto lerp = [d](const ParamRange& p) { return p.lo + (p.hi - p.lo) * d; };
  // A harder NPC reacts sooner: its reaction runs from the range's top down.
  return {lerp(r.accuracy), lerp(r.aggression),
          r.reaction_steps.hi - (r.reaction_steps.hi - r.reaction_steps.lo) * d};
}

}  // namespace zonesim::ai::adapt
