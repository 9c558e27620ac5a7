// Decision trees choose the action a written-out rule table gives; fuzzy states blend their
// outputs by membership and change gradually across a threshold.

#include <gtest/gtest.h>

#include <cmath>

#include "ai/decision/decision_tree.h"
#include "ai/decision/fuzzy_machine.h"

namespace zonesim::ai {
namespace {

enum Action { kFlee, kReload, kShoot, kApproach, kIdle };
enum Input { kHealth, kAmmo, kDistance };

// The rules as plain code: what the tree must reproduce.
int rules(const double* in) {
  if (in[kHealth] < 25) return kFlee;
  if (in[kDistance] < 20) return in[kAmmo] < 1 ? kReload : kShoot;
  return in[kDistance] < 60 ? kApproach : kIdle;
}

TEST(DecisionTree, MatchesTheRuleTableEverywhereOnAGrid) {
  DecisionTree t;
  int flee = t.addLeaf(kFlee), reload = t.addLeaf(kReload), shoot = t.addLeaf(kShoot);
  int approach = t.addLeaf(kApproach), idle = t.addLeaf(kIdle);
  int ammo = t.addTest(kAmmo, 1, reload, shoot);
  int far = t.addTest(kDistance, 60, approach, idle);
  int near = t.addTest(kDistance, 20, ammo, far);
  t.addTest(kHealth, 25, flee, near);
  EXPECT_EQ(t.size(), 9);
  int maxDepth = 0;
  for (double h = 0; h <= 100; h += 5) {
    for (double a = 0; a <= 3; a += 0.5) {
      for (double d = 0; d <= 100; d += 2.5) {
        double in[3] = {h, a, d};
        int depth = 0;
        ASSERT_EQ(t.decide(in, &depth), rules(in)) << h << " " << a << " " << d;
        maxDepth = std::max(maxDepth, depth);
      }
    }
  }
  EXPECT_EQ(maxDepth, 3);
}

TEST(Trapezoid, Shape) {
  Trapezoid t{0, 10, 20, 40};
  EXPECT_EQ(t(-1), 0.0);
  EXPECT_DOUBLE_EQ(t(5), 0.5);
  EXPECT_EQ(t(15), 1.0);
  EXPECT_DOUBLE_EQ(t(30), 0.5);
  EXPECT_EQ(t(41), 0.0);
  Trapezoid shoulder{0, 0, 10, 20};
  EXPECT_EQ(shoulder(0), 1.0);
}

TEST(FuzzyMachine, BlendsOutputsByMembership) {
  // Outputs: speed and aggression. Calm when the enemy is far, alarmed when near, with an
  // overlap from 20 to 30 where both are partly active.
  FuzzyMachine m(2);
  m.addState(0, Trapezoid{20, 30, 1e9, 1e9}, {1.0, 0.0});
  m.addState(0, Trapezoid{-1e9, -1e9, 20, 30}, {3.0, 1.0});
  std::vector<double> member, out;
  double in[1] = {50};
  m.evaluate(in, member, out);
  EXPECT_EQ(member, (std::vector<double>{1.0, 0.0}));
  EXPECT_DOUBLE_EQ(out[0], 1.0);
  in[0] = 10;
  m.evaluate(in, member, out);
  EXPECT_DOUBLE_EQ(out[0], 3.0);
  EXPECT_DOUBLE_EQ(out[1], 1.0);
  in[0] = 25;
  double total = m.evaluate(in, member, out);
  EXPECT_DOUBLE_EQ(total, 1.0);
  EXPECT_DOUBLE_EQ(member[0], 0.5);
  EXPECT_DOUBLE_EQ(out[0], 2.0);
  EXPECT_DOUBLE_EQ(out[1], 0.5);
  // Gradual: across the overlap the speed never jumps by more than the slope allows.
  double prev = 3.0;
  for (double d = 10; d <= 40; d += 0.5) {
    in[0] = d;
    m.evaluate(in, member, out);
    EXPECT_LE(std::fabs(out[0] - prev), 2.0 / 10.0 * 0.5 + 1e-12);
    prev = out[0];
  }
}

TEST(FuzzyMachine, NoActiveStateGivesZeros) {
  FuzzyMachine m(1);
  m.addState(0, Trapezoid{0, 1, 2, 3}, {5.0});
  std::vector<double> member, out;
  double in[1] = {10};
  EXPECT_EQ(m.evaluate(in, member, out), 0.0);
  EXPECT_EQ(out, (std::vector<double>{0.0}));
}

}  // namespace
}  // namespace zonesim::ai
