#include <gtest/gtest.h>

#include <cmath>

#include "test_helpers.h"
#include "zone_node/population.h"
#include "zone_node/systems/flock_movement.h"
#include "zone_node/systems/neighbourhood.h"
#include "zone_node/systems/npc_movement.h"

namespace zonesim::zone {
namespace {

/// Wanderers of testing::npcScene plus a flocking population packed in the middle.
Scene mixedScene(double alignment) {
  Scene s = testing::npcScene(50);
  s.halo_width = 3;
  NpcPopulation f;
  f.count = 300;
  f.region = {{85, 0, 85}, {115, 0, 115}};
  f.flock.enabled = true;
  f.flock.alignment_weight = alignment;
  s.npcs.push_back(f);
  return s;
}

/// Local order of the flockers: per flocker, |mean unit heading| over the flockers within
/// `radius` (itself included), averaged. Random headings give about 1/sqrt(neighbours), one
/// common heading per neighbourhood gives 1 (a flock may split into groups that head apart).
double localOrder(const EntityStore& store, double radius) {
  std::vector<std::size_t> who;
  for (std::size_t i = 0; i < store.size(); ++i)
    if (store.npc[i].flock >= 0 && std::hypot(store.vel[i].x(), store.vel[i].z()) > 1e-9)
      who.push_back(i);
  double total = 0;
  for (std::size_t i : who) {
    double x = 0, z = 0;
    int n = 0;
    for (std::size_t j : who) {
      if (std::hypot(store.pos[j].x() - store.pos[i].x(), store.pos[j].z() - store.pos[i].z()) >=
          radius)
        continue;
      double speed = std::hypot(store.vel[j].x(), store.vel[j].z());
      x += store.vel[j].x() / speed;
      z += store.vel[j].z() / speed;
      ++n;
    }
    total += std::hypot(x, z) / n;
  }
  return total / double(who.size());
}

/// Runs the scene's NPCs for `seconds`: wanderers by stepNpcs, flockers by FlockMovement.
EntityStore run(const Scene& s, double seconds, bool flocks) {
  EntityStore store;
  forEachInitialEntity(s, [&](const EntityRecordData& r) { store.add(r); });
  FlockMovement flock(s);
  for (int t = 0; t < int(seconds / s.dt); ++t) {
    stepNpcs(s, store, Neighbourhood{}, t * s.dt, s.dt);
    if (flocks) flock.step(store, nullptr, s.dt);
    for (std::size_t i = 0; i < store.size(); ++i) {
      EXPECT_GE(store.pos[i].x(), s.world.min.x);
      EXPECT_LE(store.pos[i].x(), s.world.max.x);
      EXPECT_GE(store.pos[i].z(), s.world.min.z);
      EXPECT_LE(store.pos[i].z(), s.world.max.z);
      EXPECT_EQ(store.pos[i].y(), s.world.min.y);
    }
  }
  return store;
}

TEST(FlockMovement, FlockersAlignAndWanderersKeepTheirOwnPath) {
  Scene s = mixedScene(1.0);
  EntityStore start;
  forEachInitialEntity(s, [&](const EntityRecordData& r) { start.add(r); });
  std::size_t flockers = 0;
  for (const NpcData& n : start.npc) flockers += n.flock == 1;
  EXPECT_EQ(flockers, 300u);
  double before = localOrder(start, 3.0);

  EntityStore with = run(s, 20, true);
  EntityStore still = run(s, 20, false);  // the flockers stand still without the system
  double after = localOrder(with, 3.0);
  for (std::size_t i = 0; i < with.size(); ++i) {
    if (with.npc[i].flock >= 0) {
      EXPECT_LE(std::hypot(with.vel[i].x(), with.vel[i].z()), s.npcs[1].flock.max_speed + 1e-9);
      EXPECT_EQ(still.pos[i], start.pos[i]) << "stepNpcs moved a flocking NPC";
    } else {
      EXPECT_EQ(with.pos[i], still.pos[i]) << "a wanderer's path depends on the flock";
    }
  }
  // Without alignment the headings stay disordered: the measure can tell.
  double unaligned = localOrder(run(mixedScene(0.0), 20, true), 3.0);
  std::printf("local order: start %.3f, after 20 s %.3f, without alignment %.3f\n", before, after,
              unaligned);
  EXPECT_LT(before, 0.4);
  EXPECT_GT(after, 0.85);
  EXPECT_LT(unaligned, 0.6);
}

}  // namespace
}  // namespace zonesim::zone
