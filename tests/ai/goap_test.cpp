// GOAP: the cheapest plan on small domains whose answer is known, and on random domains
// checked against an exhaustive search of every world state.

#include <gtest/gtest.h>

#include <limits>

#include "ai/goap/goap_planner.h"
#include "common/rng.h"

namespace zonesim::ai {
namespace {

std::uint64_t bit(int i) {
  return std::uint64_t(1) << i;
}
FactSet set(int fact, bool value = true) {
  return FactSet{bit(fact), value ? bit(fact) : 0};
}
FactSet both(FactSet a, FactSet b) {
  return FactSet{a.mask | b.mask, a.values | b.values};
}

// Kill the enemy: with a gun (fetch 2, load 1, shoot 1 = 4) or a knife (fetch 1, approach 3,
// stab 1 = 5).
struct Hunt {
  GoapPlanner p;
  int gun, loaded, knife, near, dead;
  int getGun, load, shoot, getKnife, approach, stab;
  Hunt(double approachCost) {
    gun = p.addFact("has_gun");
    loaded = p.addFact("loaded");
    knife = p.addFact("has_knife");
    near = p.addFact("near_enemy");
    dead = p.addFact("enemy_dead");
    getGun = p.addAction({"get_gun", {}, set(gun), 2});
    load = p.addAction({"load", set(gun), set(loaded), 1});
    shoot = p.addAction({"shoot", set(loaded), both(set(dead), set(loaded, false)), 1});
    getKnife = p.addAction({"get_knife", {}, set(knife), 1});
    approach = p.addAction({"approach", {}, set(near), approachCost});
    stab = p.addAction({"stab", both(set(knife), set(near)), set(dead), 1});
  }
};

TEST(Goap, PicksTheCheapestOfTwoKnownPlans) {
  Hunt gunWins(3.0);
  std::vector<int> plan;
  double cost = 0;
  ASSERT_TRUE(gunWins.p.plan(0, set(gunWins.dead), plan, &cost));
  EXPECT_EQ(plan, (std::vector<int>{gunWins.getGun, gunWins.load, gunWins.shoot}));
  EXPECT_DOUBLE_EQ(cost, 4.0);

  Hunt knifeWins(1.0);
  ASSERT_TRUE(knifeWins.p.plan(0, set(knifeWins.dead), plan, &cost));
  EXPECT_DOUBLE_EQ(cost, 3.0);
  ASSERT_EQ(plan.size(), 3u);
  EXPECT_EQ(plan.back(), knifeWins.stab);

  // Already holding a loaded gun: one shot.
  ASSERT_TRUE(
      gunWins.p.plan(bit(gunWins.gun) | bit(gunWins.loaded), set(gunWins.dead), plan, &cost));
  EXPECT_EQ(plan, (std::vector<int>{gunWins.shoot}));
  // Goal already true: the empty plan.
  ASSERT_TRUE(gunWins.p.plan(bit(gunWins.dead), set(gunWins.dead), plan, &cost));
  EXPECT_TRUE(plan.empty());
  EXPECT_EQ(cost, 0.0);
}

TEST(Goap, UnreachableGoalHasNoPlan) {
  GoapPlanner p;
  int a = p.addFact("a"), b = p.addFact("b");
  p.addAction({"make_a", {}, set(a), 1});
  std::vector<int> plan;
  EXPECT_FALSE(p.plan(0, set(b), plan));
  EXPECT_TRUE(plan.empty());
  EXPECT_EQ(p.fact("b"), b);
  EXPECT_EQ(p.fact("c"), -1);
}

// Dijkstra over all 2^n states by repeated relaxation (n is small).
double exhaustive(const GoapPlanner& p, int n, std::uint64_t start, const FactSet& goal) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> d(std::size_t(1) << n, inf);
  d[start] = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::uint64_t s = 0; s < d.size(); ++s) {
      if (d[s] == inf) continue;
      for (const auto& a : p.actions()) {
        if (!a.preconditions.satisfiedBy(s)) continue;
        std::uint64_t t = a.effects.applyTo(s);
        if (d[s] + a.cost < d[t] - 1e-12) {
          d[t] = d[s] + a.cost;
          changed = true;
        }
      }
    }
  }
  double best = inf;
  for (std::uint64_t s = 0; s < d.size(); ++s) {
    if (goal.satisfiedBy(s)) best = std::min(best, d[s]);
  }
  return best == inf ? -1.0 : best;
}

TEST(Goap, RandomDomainsMatchExhaustiveSearch) {
  const int n = 6;
  int solved = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    Pcg32 rng(seed, 17);
    GoapPlanner p;
    for (int i = 0; i < n; ++i) p.addFact("f" + std::to_string(i));
    auto randomSet = [&](int maxFacts) {
      FactSet f;
      int k = int(rng.next() % std::uint32_t(maxFacts + 1));
      for (int i = 0; i < k; ++i) {
        int b = int(rng.next() % n);
        f.mask |= bit(b);
        if (rng.next() & 1u) f.values |= bit(b);
      }
      return f;
    };
    for (int i = 0; i < 10; ++i) {
      p.addAction({"a" + std::to_string(i), randomSet(2), randomSet(2), 0.5 + rng.uniform() * 4});
    }
    FactSet goal = randomSet(3);
    std::uint64_t start = rng.next() % 64u;
    double expected = exhaustive(p, n, start, goal);
    std::vector<int> plan;
    double cost = -1;
    ASSERT_EQ(p.plan(start, goal, plan, &cost), expected >= 0) << "seed " << seed;
    if (expected < 0) continue;
    ++solved;
    EXPECT_NEAR(cost, expected, 1e-9) << "seed " << seed;
    // Replaying the plan reaches the goal at the reported cost.
    std::uint64_t s = start;
    double total = 0;
    for (int a : plan) {
      ASSERT_TRUE(p.actions()[std::size_t(a)].preconditions.satisfiedBy(s));
      s = p.actions()[std::size_t(a)].effects.applyTo(s);
      total += p.actions()[std::size_t(a)].cost;
    }
    EXPECT_TRUE(goal.satisfiedBy(s));
    EXPECT_NEAR(total, cost, 1e-9);
  }
  EXPECT_GT(solved, 20);
}

}  // namespace
}  // namespace zonesim::ai
