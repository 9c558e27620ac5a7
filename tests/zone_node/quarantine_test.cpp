// A walker whose state turns non-finite is frozen where it stood and counted once in the zone's
// `quarantined` counter; its NaN reaches nobody: the others stay finite, none is counted, and
// those that never came near it move exactly as in a run where it was healthy.
#include "zone_node/quarantine.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "zone_node/cluster/checkpoint.h"
#include "zone_node/population.h"
#include "zone_node/zone_fixture.h"

namespace zonesim::zone {
namespace {

constexpr int kTicks = 60;  // 2 s: a walker covers at most 6 m

struct Outcome {
  std::vector<EntityRecordData> end;
  std::uint64_t quarantined = 0;
  std::uint64_t quarantined_first_tick = 0;
  std::size_t non_finite_seen = 0;  // entity states read non-finite after a tick
  std::uint64_t conservation_failures = 0;
};

/// Runs the scene from `start` (as a restart image) and records every entity at the end.
Outcome runFrom(const Scene& scene, const std::vector<EntityRecordData>& start) {
  CheckpointImage image;
  image.ranks = 1;
  image.entities = start;
  ZoneNode node(scene, MPI_COMM_WORLD, testing::localZone(1), &image);
  Outcome r;
  for (int t = 0; t < kTicks; ++t) {
    node.tick();
    if (t == 0) r.quarantined_first_tick = node.counters().quarantined;
    r.quarantined += node.counters().quarantined;
    const EntityStore& s = node.store();
    for (std::size_t i = 0; i < s.size(); ++i)
      r.non_finite_seen += !(s.pos[i].allFinite() && s.vel[i].allFinite());
  }
  for (std::size_t i = 0; i < node.store().size(); ++i) r.end.push_back(node.store().record(i));
  std::sort(r.end.begin(), r.end.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  r.conservation_failures = node.conservation().failures;
  return r;
}

TEST(Quarantine, ANonFiniteNpcIsFrozenCountedOnceAndSpreadsToNoOne) {
  Scene scene = testing::npcScene(40);
  scene.npcs[0].separation_radius = 3;  // walkers read each other's positions
  std::vector<EntityRecordData> start;
  forEachInitialEntity(scene, [&](const EntityRecordData& e) { start.push_back(e); });
  std::sort(start.begin(), start.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  ASSERT_EQ(start.size(), 40u);
  // The sick walker stands 1 m from a neighbour, inside its separation radius.
  start[0].pos = start[1].pos + Vec3(1, 0, 0);
  std::vector<EntityRecordData> sick = start;
  sick[0].vel = Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);

  Outcome healthy = runFrom(scene, start);
  Outcome run = runFrom(scene, sick);
  EXPECT_EQ(healthy.quarantined, 0u);
  EXPECT_EQ(run.quarantined_first_tick, 1u);
  EXPECT_EQ(run.quarantined, 1u);  // held frozen after that, not counted again
  EXPECT_EQ(run.non_finite_seen, 0u);
  EXPECT_EQ(run.conservation_failures, 0u);
  ASSERT_EQ(run.end.size(), start.size());
  EXPECT_EQ(run.end[0].pos, start[0].pos);  // where the tick found it
  EXPECT_EQ(run.end[0].vel, Vec3::Zero());

  int moved = 0, far = 0;
  for (std::size_t k = 1; k < start.size(); ++k) {
    moved += run.end[k].pos != start[k].pos;
    // Beyond 2 x 6 m of travel plus the separation radius, it never read the sick walker.
    if ((start[k].pos - start[0].pos).norm() < 20) continue;
    ++far;
    EXPECT_EQ(run.end[k].pos, healthy.end[k].pos) << "entity " << k;
    EXPECT_EQ(run.end[k].vel, healthy.end[k].vel) << "entity " << k;
  }
  EXPECT_EQ(moved, 39);
  EXPECT_GT(far, 30);
}

// The guard's one-pass check over the columns finds every kind of non-finite value in every
// column, in the first row, the last (the pass's tail) and one between.
TEST(Quarantine, EveryNonFiniteValueInAnyColumnOfAnyRowIsFound) {
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  for (std::size_t rows : {1u, 6u, 7u}) {
    for (std::size_t row : {std::size_t(0), rows / 2, rows - 1}) {
      for (int column = 0; column < 3; ++column) {
        for (double value : bad) {
          EntityStore store;
          for (std::size_t k = 0; k < rows; ++k) {
            EntityRecordData r;
            r.id = EntityId{k + 1};
            r.pos = Vec3(double(k), 0, 1);
            store.add(r);
          }
          Quarantine guard;
          guard.begin(store);
          if (column == 0) store.pos[row].z() = value;
          if (column == 1) store.vel[row].y() = value;
          if (column == 2) store.rot[row].w() = value;
          EXPECT_EQ(guard.apply(store), 1u)
              << rows << " rows, row " << row << ", column " << column;
          EXPECT_TRUE(guard.holds(EntityId{row + 1}));
          EXPECT_EQ(store.pos[row], Vec3(double(row), 0, 1));
          EXPECT_EQ(Quarantine().apply(store), 0u) << "the frozen row is finite again";
        }
      }
    }
  }
}

}  // namespace
}  // namespace zonesim::zone
