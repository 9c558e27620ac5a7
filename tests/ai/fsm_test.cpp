// State machines: the YAML guard makes exactly the transitions of the hand-coded one, the
// hysteresis stops flicker, and malformed files are rejected with file:line.

#include <gtest/gtest.h>

#include <algorithm>

#include "ai/fsm/guard_machine.h"
#include "ai/fsm/machine.h"
#include "ai/parse_error.h"
#include "common/rng.h"

namespace zonesim::ai {
namespace {

std::string guardFile() {
  return std::string(ZONESIM_SOURCE_DIR) + "/tests/ai/data/guard.yaml";
}

TEST(Fsm, InterpretedGuardMatchesHandCodedGuard) {
  MachineDef def = loadMachineYaml(guardFile());
  ASSERT_EQ(def.states.size(), 4u);
  const char* names[] = {"patrol", "chase", "attack", "flee"};
  for (int i = 0; i < 4; ++i) ASSERT_EQ(def.stateIndex(names[i]), i);

  int transitions = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    Pcg32 rng(seed, 4);
    GuardMachine coded;
    MachineState data = startMachine(def);
    GuardInputs in;
    // A random walk of the inputs that crosses every threshold many times, noise included.
    for (int tick = 0; tick < 2000; ++tick) {
      in.enemy_distance = std::clamp(
          in.enemy_distance > 100 ? 20.0 : in.enemy_distance + rng.uniform(-2.0, 2.0), 0.0, 30.0);
      in.health = std::clamp(in.health + rng.uniform(-6.0, 6.0), 0.0, 100.0);
      double inputs[2] = {in.enemy_distance, in.health};
      bool a = coded.step(in);
      bool b = stepMachine(def, data, inputs);
      ASSERT_EQ(a, b) << "seed " << seed << " tick " << tick;
      ASSERT_EQ(int(coded.state()), data.state) << "seed " << seed << " tick " << tick;
      ASSERT_EQ(coded.ticksInState(), data.ticksInState(def));
      transitions += a;
    }
  }
  EXPECT_GT(transitions, 500) << "the walk must exercise the machine";
}

TEST(Fsm, HysteresisStopsFlickerAtAThreshold) {
  GuardMachine guard;
  int changes = 0;
  // Distance jitters around the chase threshold: one transition in, none back out.
  for (int tick = 0; tick < 100; ++tick) {
    changes += guard.step(GuardInputs{tick % 2 ? 9.5 : 10.5, 100.0});
  }
  EXPECT_EQ(changes, 1);
  EXPECT_EQ(guard.state(), GuardMachine::State::Chase);
  // Fleeing lasts its minimum even if health recovers at once.
  guard.step(GuardInputs{5.0, 10.0});
  ASSERT_EQ(guard.state(), GuardMachine::State::Flee);
  for (int i = 0; i < 5; ++i) {
    guard.step(GuardInputs{5.0, 90.0});
    EXPECT_EQ(guard.state(), GuardMachine::State::Flee);
  }
  guard.step(GuardInputs{5.0, 90.0});
  EXPECT_EQ(guard.state(), GuardMachine::State::Patrol);
}

TEST(Fsm, HierarchicalMachineEntersSubstatesAndOuterTransitionsWin) {
  MachineDef def =
      loadMachineYaml(std::string(ZONESIM_SOURCE_DIR) + "/tests/ai/data/guard_hierarchical.yaml");
  const int patrol = def.stateIndex("patrol"), combat = def.stateIndex("combat");
  const int chase = def.stateIndex("chase"), attack = def.stateIndex("attack");
  const int flee = def.stateIndex("flee");
  EXPECT_EQ(def.states[std::size_t(chase)].parent, combat);
  EXPECT_EQ(def.initial, patrol);
  MachineState m = startMachine(def);
  auto step = [&](double distance, double health) {
    double in[2] = {distance, health};
    return stepMachine(def, m, in);
  };
  EXPECT_TRUE(step(5, 100));
  EXPECT_EQ(m.state, chase) << "entering combat enters its initial substate";
  // Switching inside combat does not restart combat's timer: after 10 ticks in combat the
  // enemy moving away ends combat although attack was entered only just now.
  for (int i = 0; i < 9; ++i) step(5, 100);
  EXPECT_TRUE(step(1, 100));
  EXPECT_EQ(m.state, attack);
  EXPECT_EQ(m.ticksInState(def), 0);
  EXPECT_TRUE(step(20, 100));
  EXPECT_EQ(m.state, patrol);
  // Back into combat, then hurt while attacking: the outer transition fires from the substate.
  step(5, 100);
  step(1, 100);
  ASSERT_EQ(m.state, attack);
  EXPECT_TRUE(step(1, 10));
  EXPECT_EQ(m.state, flee);
  // Outer min_ticks counts from entering combat: a far enemy right after entry does not end it.
  for (int i = 0; i < 6; ++i) step(50, 100);
  ASSERT_EQ(m.state, patrol);
  step(5, 100);
  ASSERT_EQ(m.state, chase);
  EXPECT_FALSE(step(20, 100));
  EXPECT_EQ(m.state, chase);
}

int errorLine(const std::string& text) {
  try {
    parseMachineYaml(text, "m.yaml");
  } catch (const ParseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("m.yaml:" + std::to_string(e.line()) + ": ", 0), 0u)
        << e.what();
    return e.line();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return -1;
}

TEST(Fsm, MalformedMachinesNameTheLine) {
  const std::string head = "machine: m\ninputs: [x]\nstates:\n";
  EXPECT_EQ(errorLine(head + "  - name: a\n    transitions:\n      - {to: b}\n"), 6);
  EXPECT_EQ(errorLine(head + "  - name: a\n    transitions:\n      - {to: a, when: y < 1}\n"), 6);
  EXPECT_EQ(errorLine(head + "  - name: a\n    transitions:\n      - {to: a, when: x ~ 1}\n"), 6);
  EXPECT_EQ(errorLine(head + "  - name: a\n    transitions:\n      - {to: a, when: x < z}\n"), 6);
  EXPECT_EQ(errorLine(head + "  - name: a\n    transitions:\n      - {to: a, after: 3}\n"), 6);
  EXPECT_EQ(errorLine(head + "  - name: a\n  - name: a\n"), 5);
  EXPECT_EQ(errorLine(head + "  - name: a\ninitial: q\n"), 5);
  EXPECT_EQ(errorLine("machine: m\nstates:\n  - name: a\n"), 1);
  EXPECT_EQ(errorLine(head + "  - name: a\n    initial: b\n    substates:\n      - name: c\n"), 5);
  EXPECT_EQ(errorLine(head + "  - name: a\n    initial: b\n"), 5);
  EXPECT_EQ(errorLine(head + "  - name: a\n    colour: red\n"), 5);
  EXPECT_EQ(errorLine("machine: m\ninputs: [x\nstates: []\n"), 3);
}

TEST(Fsm, MissingFileIsAnError) {
  EXPECT_THROW(loadMachineYaml(guardFile() + ".missing"), ParseError);
}

}  // namespace
}  // namespace zonesim::ai
