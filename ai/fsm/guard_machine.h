#pragma once
// The guard's behaviour written by hand: patrol, chase an enemy in sight, attack in reach, flee
// when hurt. Thresholds differ on the way in and out (see at 10, lose at 15; attack under 2,
// stop over 3; flee under 25 health, return over 60) so that noise on a threshold does not
// make the guard flicker between states. data/guard.yaml in the tests is the same machine as
// data; a test checks that both make the same transitions.

namespace zonesim::ai {

/// What the guard perceives each tick.
struct GuardInputs {
  double enemy_distance = 1e9;  ///< distance to the nearest enemy
  double health = 100.0;        ///< own health, 0..100
};

/// Hand-coded guard state machine.
class GuardMachine {
 public:
  /// Guard states.
  enum class State { Patrol, Chase, Attack, Flee };

  /// A guard starting to patrol.
  GuardMachine() = default;
  /// A guard resumed in `state` entered `ticks` ago (state kept outside, e.g. by a zone agent).
  GuardMachine(State state, int ticks) : state_(state), ticks_(ticks) {}

  /// Advances one tick; returns true when the state changed.
  bool step(const GuardInputs& in);
  /// Current state.
  State state() const { return state_; }
  /// Ticks since the last transition.
  int ticksInState() const { return ticks_; }

 private:
  State state_ = State::Patrol;
  int ticks_ = 0;
};

}  // namespace zonesim::ai
