// The walker neighbourhood answers like a brute-force scan, in id order, ghosts included.
#include "zone_node/systems/neighbourhood.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "common/rng.h"
#include "zone_node/entity_store.h"
#include "zone_node/ghost_store.h"

namespace zonesim::zone {
namespace {

EntityRecordData walker(std::uint64_t id, double x, double z, EntityKind kind = EntityKind::Npc) {
  EntityRecordData r;
  r.id = EntityId{id};
  r.kind = kind;
  r.pos = Vec3(x, 0, z);
  return r;
}

TEST(Neighbourhood, MatchesBruteForceInIdOrder) {
  Pcg32 rng(3, 1);
  EntityStore store;
  GhostStore ghosts;
  // Ids in shuffled order so that id order differs from storage order.
  for (int i = 0; i < 600; ++i)
    store.add(walker(1000 + (i * 7919) % 600, rng.uniform(0, 50), rng.uniform(0, 50)));
  for (int i = 0; i < 200; ++i)
    ghosts.add(EntityId{5000 + std::uint64_t(i)}, EntityKind::Npc,
               Vec3(rng.uniform(50, 55), 0, rng.uniform(0, 50)), Vec3::Zero(), Quat::Identity(),
               BodyData{}, 1);
  store.add(walker(9000, 25, 25, EntityKind::RigidBody));  // not a walker: never returned

  const double radius = 3.0;
  Neighbourhood near;
  near.build(store, &ghosts, radius);
  EXPECT_EQ(near.size(), 800u);
  std::vector<Neighbour> found;
  for (std::size_t i = 0; i < store.size(); ++i) {
    if (store.kind[i] != EntityKind::Npc) continue;
    near.query(store.pos[i], radius, store.id[i], found);
    std::vector<std::uint64_t> expected;
    auto consider = [&](EntityId id, const Vec3& p) {
      if (id == store.id[i]) return;
      double dx = p.x() - store.pos[i].x(), dz = p.z() - store.pos[i].z();
      if (dx * dx + dz * dz <= radius * radius) expected.push_back(id.value);
    };
    for (std::size_t j = 0; j < store.size(); ++j)
      if (store.kind[j] == EntityKind::Npc) consider(store.id[j], store.pos[j]);
    for (std::size_t j = 0; j < ghosts.size(); ++j) consider(ghosts.id[j], ghosts.pos[j]);
    std::sort(expected.begin(), expected.end());
    std::vector<std::uint64_t> got;
    for (const Neighbour& n : found) got.push_back(n.id.value);
    ASSERT_EQ(got, expected) << "around walker " << store.id[i].value;
  }
}

TEST(Neighbourhood, SmallerQueryRadiusAndSparseWorld) {
  EntityStore store;
  store.add(walker(1, 0, 0));
  store.add(walker(2, 1.5, 0));
  store.add(walker(3, 1e5, 1e5));  // far away: the grid stays small
  Neighbourhood near;
  near.build(store, nullptr, 2.0);
  std::vector<Neighbour> found;
  near.query(store.pos[0], 2.0, store.id[0], found);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].id.value, 2u);
  near.query(store.pos[0], 1.0, store.id[0], found);
  EXPECT_TRUE(found.empty());
}

}  // namespace
}  // namespace zonesim::zone
