// The neighbour grid finds exactly the agents a brute-force scan finds, in the canonical order
// (rows of cells, then ids), and flock steps are bitwise independent of storage order and of
// how agents are split between owned and ghost sets (what decomposition across ranks needs).

#include "crowd/neighbour_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <set>

#include "crowd/flock.h"
#include "crowd_test_util.h"

namespace zonesim::crowd {
namespace {

test::AgentArrays randomAgents(int n, double extent, std::uint64_t seed) {
  test::AgentArrays a;
  Pcg32 rng(seed, 3);
  for (int i = 0; i < n; ++i)
    a.add(std::uint64_t(rng.next()) << 16 | std::uint64_t(i),
          Vec2{rng.uniform(-extent, extent), rng.uniform(-extent, extent)},
          Vec2{rng.uniform(-1, 1), rng.uniform(-1, 1)});
  return a;
}

TEST(NeighbourGrid, FindsTheSameNeighboursAsBruteForce) {
  auto a = randomAgents(800, 20.0, 1);
  auto g = randomAgents(200, 25.0, 2);
  NeighbourGrid grid;
  grid.build(a.span(), g.ghosts(), 1.5);
  ASSERT_EQ(grid.entries().size(), 1000u);
  const double r = 1.5;
  for (std::size_t i = 0; i < a.pos.size(); i += 7) {
    std::set<std::uint64_t> expect, got;
    for (std::size_t j = 0; j < a.pos.size(); ++j)
      if (length(a.pos[j] - a.pos[i]) < r) expect.insert(a.ids[j]);
    for (std::size_t j = 0; j < g.pos.size(); ++j)
      if (length(g.pos[j] - a.pos[i]) < r) expect.insert(g.ids[j]);
    std::vector<const GridEntry*> visited;
    grid.forEachNear(a.pos[i], r, [&](const GridEntry& e) {
      visited.push_back(&e);
      if (length(e.pos - a.pos[i]) < r) got.insert(e.id);
    });
    EXPECT_EQ(expect, got) << "agent " << i;
    // Canonical order: non-decreasing cell, ids ascending within a cell.
    for (std::size_t k = 1; k < visited.size(); ++k) {
      ASSERT_LE(visited[k - 1]->cell, visited[k]->cell);
      if (visited[k - 1]->cell == visited[k]->cell) {
        ASSERT_LT(visited[k - 1]->id, visited[k]->id);
      }
    }
  }
}

TEST(NeighbourGrid, TheBoxQueryVisitsTheDiscsEntriesInTheSameOrder) {
  // The flow crowd sums separation over forEachRowInBox: the entries within the disc must
  // come exactly as forEachRowNear gives them, for radii below and above the cell side.
  auto a = randomAgents(900, 20.0, 11);
  auto g = randomAgents(150, 24.0, 12);
  NeighbourGrid grid;
  grid.build(a.span(), g.ghosts(), 2.0);
  int extra = 0;
  for (double r : {0.6, 1.0, 2.0, 3.5}) {
    for (std::size_t i = 0; i < a.pos.size(); i += 5) {
      const Vec2 p = a.pos[i];
      std::vector<std::int32_t> inDisc, inBox;
      int nearVisits = 0, boxVisits = 0;
      grid.forEachRowNear(p, r, [&](std::int32_t begin, std::int32_t end) {
        for (std::int32_t k = begin; k < end; ++k, ++nearVisits)
          if (lengthSq(grid.entries()[k].pos - p) < r * r) inDisc.push_back(k);
      });
      grid.forEachRowInBox(p, r, [&](std::int32_t begin, std::int32_t end) {
        for (std::int32_t k = begin; k < end; ++k, ++boxVisits)
          if (lengthSq(grid.entries()[k].pos - p) < r * r) inBox.push_back(k);
      });
      EXPECT_EQ(inDisc, inBox) << "agent " << i << ", radius " << r;
      EXPECT_GE(boxVisits, nearVisits);
      extra += boxVisits - nearVisits;
    }
  }
  EXPECT_GT(extra, 0);  // the box does reach cells past the chords: the case is exercised
}

TEST(NeighbourGrid, EntriesPointBackToTheirSource) {
  auto a = randomAgents(300, 10.0, 5);
  auto g = randomAgents(50, 10.0, 6);
  NeighbourGrid grid;
  grid.build(a.span(), g.ghosts(), 2.0);
  for (const GridEntry& e : grid.entries()) {
    if (e.src >= 0) {
      EXPECT_EQ(a.ids[e.src], e.id);
      EXPECT_EQ(a.pos[e.src], e.pos);
    } else {
      EXPECT_EQ(g.ids[-1 - e.src], e.id);
      EXPECT_EQ(g.pos[-1 - e.src], e.pos);
    }
  }
}

// The state of every agent keyed by id, so runs that store agents differently compare equal.
std::map<std::uint64_t, std::pair<Vec2, Vec2>> byId(const test::AgentArrays& a) {
  std::map<std::uint64_t, std::pair<Vec2, Vec2>> m;
  for (std::size_t i = 0; i < a.ids.size(); ++i) m[a.ids[i]] = {a.pos[i], a.vel[i]};
  return m;
}

// Two "ranks'" agents back in one array after a split step, `first` stored first.
test::AgentArrays joined(const test::AgentArrays& first, const test::AgentArrays& second) {
  test::AgentArrays all;
  for (const auto* part : {&first, &second})
    for (std::size_t i = 0; i < part->ids.size(); ++i)
      all.add(part->ids[i], part->pos[i], part->vel[i]);
  return all;
}

TEST(NeighbourGrid, FlockStepsAreBitwiseIndependentOfStorageOrder) {
  auto a = randomAgents(1500, 15.0, 9);
  test::AgentArrays b;
  std::vector<std::size_t> perm(a.ids.size());
  std::iota(perm.begin(), perm.end(), 0);
  Pcg32 rng(4, 4);
  for (std::size_t i = perm.size(); i > 1; --i) std::swap(perm[i - 1], perm[rng.next() % i]);
  for (std::size_t k : perm) b.add(a.ids[k], a.pos[k], a.vel[k]);
  Flock fa{FlockSettings{}}, fb{FlockSettings{}};
  for (int s = 0; s < 20; ++s) {
    fa.step(a.span(), {}, 1.0 / 30);
    fb.step(b.span(), {}, 1.0 / 30);
  }
  EXPECT_EQ(byId(a), byId(b));
}

TEST(NeighbourGrid, OwnedPlusGhostSplitsMatchTheWholeFlockBitwise) {
  // Two "ranks" split at x = 0, each seeing the other's agents as ghosts, reproduce the
  // single-rank step exactly; ownership is re-split every step (agents migrate).
  auto whole = randomAgents(1200, 12.0, 11);
  auto split = whole;
  Flock single{FlockSettings{}}, left{FlockSettings{}}, right{FlockSettings{}};
  for (int s = 0; s < 20; ++s) {
    single.step(whole.span(), {}, 1.0 / 30);
    test::AgentArrays l, r;
    for (std::size_t i = 0; i < split.ids.size(); ++i)
      (split.pos[i].x < 0 ? l : r).add(split.ids[i], split.pos[i], split.vel[i]);
    // Ghosts are read before either side writes: snapshot copies.
    test::AgentArrays lGhost = r, rGhost = l;
    left.step(l.span(), lGhost.ghosts(), 1.0 / 30);
    right.step(r.span(), rGhost.ghosts(), 1.0 / 30);
    split = joined(r, l);
  }
  EXPECT_EQ(byId(whole), byId(split));
}

TEST(NeighbourGrid, HaloOfTheNeighbourRadiusIsEnoughForBitwiseSplits) {
  // As a zone's halo does: each side sees only the other's agents within the neighbour radius
  // of the split line. The line is off the cell boundaries (as zone borders are), so cells near
  // it hold fewer agents than on one rank (those farther out are missing), which must not
  // change any sum.
  auto whole = randomAgents(1200, 12.0, 13);
  auto split = whole;
  const FlockSettings settings{};
  const double line = 1.3, halo = settings.neighbour_radius;
  Flock single{settings}, left{settings}, right{settings};
  for (int s = 0; s < 20; ++s) {
    single.step(whole.span(), {}, 1.0 / 30);
    test::AgentArrays l, r, lGhost, rGhost;
    for (std::size_t i = 0; i < split.ids.size(); ++i) {
      double x = split.pos[i].x;
      bool isLeft = x < line;
      (isLeft ? l : r).add(split.ids[i], split.pos[i], split.vel[i]);
      if (!isLeft && x < line + halo) lGhost.add(split.ids[i], split.pos[i], split.vel[i]);
      if (isLeft && x >= line - halo) rGhost.add(split.ids[i], split.pos[i], split.vel[i]);
    }
    left.step(l.span(), lGhost.ghosts(), 1.0 / 30);
    right.step(r.span(), rGhost.ghosts(), 1.0 / 30);
    split = joined(r, l);
  }
  EXPECT_EQ(byId(whole), byId(split));
}

TEST(NeighbourGrid, AnAgentsStepDoesNotDependOnWhichAgentItIsPairedWith) {
  // Flock::step sums the neighbours of two consecutive agents in one pass over the union of
  // their rows; each agent's result must be bitwise its own one-agent sum. Leaving one agent
  // out of a step (plan dt 0) shifts the pairing of every later agent in cell order (first
  // of a pair, second of a pair, or the odd one summed alone), so every other agent must end
  // the step bitwise as before. Exact overlaps exercise the per-lane coincidence counts.
  auto base = randomAgents(801, 10.0, 21);
  for (int k = 0; k < 40; k += 4) {
    Vec2 p = base.pos[std::size_t(k)], v = base.vel[std::size_t(k) + 1];
    base.add(900000 + std::uint64_t(k), p, v);
  }
  const std::size_t n = base.ids.size();
  std::vector<std::uint8_t> steer(n, 1);
  for (std::size_t leftOut : {std::size_t(0), std::size_t(5), std::size_t(6), n - 1}) {
    std::vector<double> all(n, 1.0 / 30), less(n, 1.0 / 30);
    less[leftOut] = 0.0;
    auto a = base, b = base;
    Flock fa{FlockSettings{}}, fb{FlockSettings{}};
    fa.step(a.span(), {}, 1.0 / 30, {}, StepPlan{all, steer});
    fb.step(b.span(), {}, 1.0 / 30, {}, StepPlan{less, steer});
    int differ = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (i != leftOut && (a.pos[i] != b.pos[i] || a.vel[i] != b.vel[i])) ++differ;
    EXPECT_EQ(differ, 0) << "left out " << leftOut;
    EXPECT_EQ(b.pos[leftOut], base.pos[leftOut]);
  }
}

TEST(NeighbourGrid, EveryVectorWidthGivesTheSameStepBitwise) {
  // One agent per pass, two (SSE2), four (AVX) and eight (AVX-512) where the CPU has them:
  // the same flock, with ghosts and exact overlaps, ends bitwise equal after 20 steps, and so
  // does a flock whose bodies are kept apart (a scalar pass after the sums).
  auto base = randomAgents(1001, 11.0, 23);
  for (int k = 0; k < 60; k += 6) {
    Vec2 p = base.pos[std::size_t(k)], v = base.vel[std::size_t(k) + 1];
    base.add(800000 + std::uint64_t(k), p, v);
  }
  auto ghosts = randomAgents(300, 14.0, 24);
  for (auto& id : ghosts.ids) id |= 1ULL << 62;  // disjoint from the owned ids
  for (double body : {0.0, 0.4}) {
    std::map<std::uint64_t, std::pair<Vec2, Vec2>> reference;
    for (int lanes : {1, 2, 4, 8}) {
      auto a = base;
      FlockSettings settings;
      settings.body_radius = body;
      Flock f{settings};
      int used = f.useLanes(lanes);
      EXPECT_LE(used, lanes);
      for (int s = 0; s < 20; ++s) f.step(a.span(), ghosts.ghosts(), 1.0 / 30);
      if (lanes == 1)
        reference = byId(a);
      else
        EXPECT_EQ(byId(a), reference) << lanes << " lanes (" << used << " in use), body " << body;
    }
  }
}

}  // namespace
}  // namespace zonesim::crowd
