#include "ai/fsm/guard_machine.h"

namespace zonesim::ai {

namespace {

// Fleeing must last a few ticks before the guard may calm down: hysteresis in time as well as
// in health.
constexpr int kMinFleeTicks = 5;

}  // namespace

bool GuardMachine::step(const GuardInputs& in) {
  State next = state_;
  switch (state_) {
    case State::Patrol:
      if (in.health < 25) {
        next = State::Flee;
      } else if (in.enemy_distance < 10) {
        next = State::Chase;
      }
      break;
    case State::Chase:
      if (in.health < 25) {
        next = State::Flee;
      } else if (in.enemy_distance < 2) {
        next = State::Attack;
      } else if (in.enemy_distance > 15) {
        next = State::Patrol;
      }
      break;
    case State::Attack:
      if (in.health < 25) {
        next = State::Flee;
      } else if (in.enemy_distance > 3) {
        next = State::Chase;
      }
      break;
    case State::Flee:
      if (ticks_ >= kMinFleeTicks && in.health > 60) next = State::Patrol;
      break;
  }
  if (next == state_) {
    ++ticks_;
    return false;
  }
  state_ = next;
  ticks_ = 0;
  return true;
}

}  // namespace zonesim::ai
