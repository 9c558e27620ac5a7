#pragma once
// What adaptation may change about a duelling NPC, and the one-number difficulty scale that
// the model and the rubber band speak: 0 is the gentlest NPC, 1 the deadliest.

namespace zonesim::ai::adapt {

/// An NPC's fighting parameters.
struct NpcParams {
  double accuracy = 0;        ///< chance that an attack hits
  double aggression = 0;      ///< chance to attack in an exchange once it reacts
  double reaction_steps = 0;  ///< exchanges of a round before the NPC first attacks
};

/// The range a parameter may take.
struct ParamRange {
  double lo = 0;
  double hi = 1;
  /// Whether v lies in [lo, hi].
  bool holds(double v) const { return v >= lo && v <= hi; }
};

/// The game's ranges: a difficulty in [0, 1] maps onto them, and the guards keep them.
struct NpcRanges {
  ParamRange accuracy{0.2, 0.9};
  ParamRange aggression{0.6, 1.0};
  ParamRange reaction_steps{0, 4};
};

/// The NPC of difficulty `d` (0 gentlest, 1 deadliest): every parameter moves with it, so that
/// one number orders NPCs from easy to hard. Not clamped: the guards do that.
NpcParams paramsForDifficulty(double d, const NpcRanges& ranges = {});

/// The difficulty the game starts from and falls back to.
constexpr double kDefaultDifficulty = 0.5;

}  // namespace zonesim::ai::adapt
