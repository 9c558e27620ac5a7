#include "physics/broadphase.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

namespace zonesim::physics {
namespace {

struct Scene {
  std::vector<Aabb> boxes;
  std::vector<std::uint8_t> moving;
};

Scene randomScene(std::uint32_t seed, int n) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-20.0, 20.0), size(0.1, 2.5), coin(0.0, 1.0);
  Scene s;
  for (int i = 0; i < n; ++i) {
    const Vec3 c(pos(rng), pos(rng), pos(rng));
    const Vec3 h(size(rng), size(rng), size(rng));
    s.boxes.push_back(Aabb{c - h, c + h});
    s.moving.push_back(coin(rng) < 0.8 ? 1 : 0);
  }
  // A floor much larger than a grid cell, and a pair of exactly touching boxes.
  s.boxes.push_back(Aabb{Vec3(-50, -22, -50), Vec3(50, -19, 50)});
  s.moving.push_back(0);
  s.boxes.push_back(Aabb{Vec3(30, 0, 0), Vec3(31, 1, 1)});
  s.moving.push_back(1);
  s.boxes.push_back(Aabb{Vec3(31, 0, 0), Vec3(32, 1, 1)});
  s.moving.push_back(1);
  return s;
}

TEST(Broadphase, AllAlgorithmsReturnTheBruteForcePairSet) {
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    Scene s = randomScene(seed, 400);
    Broadphase reference(BroadphaseKind::BruteForce);
    Broadphase sap(BroadphaseKind::SweepAndPrune), grid(BroadphaseKind::UniformGrid, 1.5),
        tree(BroadphaseKind::AabbTree);
    std::mt19937_64 rng(seed + 100);
    std::normal_distribution<double> jitter(0.0, 0.3);
    // Several frames with motion: exercises the tree's reinsertion and the sweep's reuse.
    for (int frame = 0; frame < 4; ++frame) {
      std::vector<ProxyPair> expected, got;
      reference.findPairs(s.boxes, s.moving, expected);
      ASSERT_GT(expected.size(), 50u);
      for (Broadphase* bp : {&sap, &grid, &tree}) {
        bp->findPairs(s.boxes, s.moving, got);
        EXPECT_EQ(got, expected) << "kind " << int(bp->kind()) << " seed " << seed;
      }
      for (std::size_t i = 0; i < s.boxes.size(); ++i) {
        if (!s.moving[i]) continue;
        const Vec3 d(jitter(rng), jitter(rng), jitter(rng));
        s.boxes[i].lo += d;
        s.boxes[i].hi += d;
      }
    }
  }
}

// Kept pairs (a keep margin) against every algorithm finding all pairs anew, frame after
// frame: small moves (a few boxes leave their grown ones), large ones (all found anew), bodies
// waking and falling asleep, and a box added.
TEST(Broadphase, KeptPairsAreThePairsFoundAnewEveryFrame) {
  for (auto kind : {BroadphaseKind::BruteForce, BroadphaseKind::SweepAndPrune,
                    BroadphaseKind::UniformGrid, BroadphaseKind::AabbTree}) {
    Scene s = randomScene(7, 400);
    Broadphase fresh(BroadphaseKind::BruteForce), kept(kind, 1.5, 0.1);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> coin(0.0, 1.0);
    std::normal_distribution<double> jitter(0.0, 1.0);
    for (int frame = 0; frame < 40; ++frame) {
      std::vector<ProxyPair> expected, got;
      fresh.findPairs(s.boxes, s.moving, expected);
      kept.findPairs(s.boxes, s.moving, got);
      ASSERT_EQ(got, expected) << "kind " << int(kind) << " frame " << frame;
      // Most frames move a few boxes a little; every tenth moves them all far.
      const bool far = frame % 10 == 9;
      for (std::size_t i = 0; i < s.boxes.size(); ++i) {
        if (!s.moving[i] || (!far && coin(rng) > 0.05)) continue;
        const Vec3 d = (far ? 1.0 : 0.08) * Vec3(jitter(rng), jitter(rng), jitter(rng));
        s.boxes[i].lo += d;
        s.boxes[i].hi += d;
      }
      for (std::size_t i = 0; i + 3 < s.boxes.size(); ++i) {
        if (coin(rng) < 0.02) s.moving[i] = !s.moving[i];
      }
      if (frame == 20) {
        s.boxes.push_back(s.boxes[5].expanded(0.2));
        s.moving.push_back(1);
      }
    }
    std::printf("kind %d: %zu rebuilds, %zu boxes looked at again alone in 40 frames\n", int(kind),
                kept.rebuilds(), kept.regrown());
    EXPECT_GT(kept.regrown(), 0u);
    EXPECT_GE(kept.rebuilds(), 3u);
    EXPECT_LT(kept.rebuilds(), 40u);
  }
}

TEST(Broadphase, StaticPairsAreNeverReported) {
  Scene s;
  s.boxes = {Aabb{Vec3(0, 0, 0), Vec3(2, 2, 2)}, Aabb{Vec3(1, 1, 1), Vec3(3, 3, 3)},
             Aabb{Vec3(1.5, 1.5, 1.5), Vec3(4, 4, 4)}};
  s.moving = {0, 0, 1};
  for (auto kind : {BroadphaseKind::BruteForce, BroadphaseKind::SweepAndPrune,
                    BroadphaseKind::UniformGrid, BroadphaseKind::AabbTree}) {
    Broadphase bp(kind);
    std::vector<ProxyPair> pairs;
    bp.findPairs(s.boxes, s.moving, pairs);
    const std::vector<ProxyPair> expected = {{0, 2}, {1, 2}};
    EXPECT_EQ(pairs, expected) << "kind " << int(kind);
  }
}

}  // namespace
}  // namespace zonesim::physics
